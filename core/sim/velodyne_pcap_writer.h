#pragma once
/// Writes Velodyne firing sequences as a Velodyne capture, the way VeloView
/// records a real sensor: a classic pcap (microsecond record stamps,
/// Ethernet) of the sensor's UDP data packets, 192.168.1.201:2368 ->
/// 255.255.255.255:2368. See docs/simulator.md, "Velodyne capture".
///
/// Data packet (the manuals, single return "strongest"): 1206-byte payload
/// of 12 blocks of 100 bytes (flag 0xFF 0xEE, azimuth of the block's first
/// firing in 0.01 deg, then 32 x (distance, reflectivity): a VLP-16 block
/// holds 2 firing sequences x 16 lasers, a VLP-32C or HDL-32E block one
/// sequence of 32), the timestamp (uint32, microseconds past the hour of the
/// first firing of block 0), return mode 0x37 and the product id (VLP-16
/// 0x22, VLP-32C 0x28, HDL-32E 0x21). So 24 (VLP-16: 1327.104 us) or 12
/// (VLP-32C: 663.552 us, HDL-32E: 552.96 us) consecutive firing sequences
/// make one packet; the timing constants are the decoder's
/// (io/velodyne/velodyne_tables.h).
///
/// Record time of a packet = the sensor time it is complete (its first firing
/// + its sequences' span), rounded to the microsecond: the capture clock is the
/// sensor clock, as for a capture on a PTP-synchronised host.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "io/velodyne/velodyne_tables.h"
#include "sim/velodyne_firing.h"
#include "sim/velodyne_packet_builder.h"

namespace storey::sim {

class VelodynePcapWriter {
 public:
  /// Opens `path` for writing (truncates). `start_ns` is the absolute time
  /// of VelodyneFiring::t_ns = 0; `rotation_hz` is the spin rate (only used
  /// to continue the azimuth over the no-return sequences that fill the last
  /// packet); `cut_azimuth` [0.01 deg] is where a reader cuts frames
  /// (frameStarts). Throws storey::Error naming the file.
  VelodynePcapWriter(const std::string& path, std::int64_t start_ns, double rotation_hz,
                     velodyne::Model model = velodyne::Model::kVlp16, int cut_azimuth = 0);
  ~VelodynePcapWriter();
  VelodynePcapWriter(const VelodynePcapWriter&) = delete;
  VelodynePcapWriter& operator=(const VelodynePcapWriter&) = delete;

  /// Adds the next firing sequence; sequences must follow each other at the
  /// model's period (VLP-16 and VLP-32C 55.296 us, HDL-32E 46.08 us), else
  /// storey::Error.
  void add(const VelodyneFiring& sequence);
  /// Completes the last packet with no-return sequences and closes the file.
  /// Throws storey::Error when the file could not be written.
  void close();

  std::int64_t packets() const { return builder_.packets(); }
  /// The frame starts of the packets written (VelodynePacketBuilder::frameStarts).
  const std::vector<std::int64_t>& frameStarts() const { return builder_.frameStarts(); }
  std::uint64_t bytes() const { return bytes_; }

 private:
  void writePacket();
  void writeBytes(const void* data, std::size_t size);

  std::string path_;
  std::FILE* file_ = nullptr;
  VelodynePacketBuilder builder_;
  BuiltPacket packet_;
  std::vector<std::uint8_t> frame_;  ///< link-layer frame buffer
  std::uint64_t bytes_ = 0;
  std::uint16_t ip_id_ = 0;
};

}  // namespace storey::sim
