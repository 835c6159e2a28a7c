#pragma once
/// Synthetic captures written byte by byte (pcap format, Ethernet/IPv4/UDP)
/// holding synthetic Velodyne packets with known content, for tests of the
/// reader's handling of good and bad input.
#include <cstdint>
#include <string>
#include <vector>

namespace storey::test {

struct PcapRecord {
  std::int64_t t_ns = 0;            ///< record time
  std::vector<std::uint8_t> frame;  ///< link-layer bytes as captured
  std::uint32_t original_length = 0;  ///< 0 = frame.size(); larger = captured truncated
};

/// Ethernet + IPv4 + UDP around `payload`.
std::vector<std::uint8_t> udpFrame(std::uint16_t src_port, std::uint16_t dst_port,
                                   const std::vector<std::uint8_t>& payload);
/// Ethernet + IPv4 with protocol TCP (6) and a few bytes.
std::vector<std::uint8_t> tcpFrame();
/// An ARP frame (not IP).
std::vector<std::uint8_t> arpFrame();

/// Writes a classic little-endian pcap (microsecond stamps, DLT_EN10MB).
void writePcap(const std::string& path, const std::vector<PcapRecord>& records);

/// A synthetic VLP-16 data packet: every laser returns `distance_m` (a round
/// room around the sensor); block b has azimuth start + b * step (0.01 deg),
/// wrapped to [0, 36000). Dual mode repeats each azimuth for the pair and
/// gives the second block `second_distance_m` (equal = identical returns).
std::vector<std::uint8_t> vlp16Packet(std::uint32_t timestamp_us, int start_azimuth, int step,
                                      double distance_m = 5.0, bool dual = false,
                                      double second_distance_m = 5.0);

/// A spinning VLP-16 (single return) over `seconds` at `hz`: packets every
/// 1327.104 us from `t0_us` (microseconds past the hour) with azimuths starting
/// at `azimuth0`; record times = sensor times + `record_offset_ns`.
std::vector<PcapRecord> vlp16Capture(double seconds, double hz, std::uint32_t t0_us,
                                     int azimuth0 = 0, std::int64_t record_offset_ns = 1'600'000'000'000'000'000LL);

}  // namespace storey::test
