#include "pcap_fixtures.h"

#include <cmath>
#include <fstream>

namespace storey::test {
namespace {

void put16be(std::vector<std::uint8_t>& b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v >> 8);
  b[at + 1] = static_cast<std::uint8_t>(v);
}
void put16le(std::vector<std::uint8_t>& b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v);
  b[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
void put32le(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) b[at + k] = static_cast<std::uint8_t>(v >> (8 * k));
}
void write32(std::ofstream& out, std::uint32_t v) {
  char b[4];
  for (int k = 0; k < 4; ++k) b[k] = static_cast<char>(v >> (8 * k));
  out.write(b, 4);
}

std::vector<std::uint8_t> ipv4Frame(std::uint8_t protocol, std::size_t ip_payload) {
  std::vector<std::uint8_t> f(14 + 20 + ip_payload, 0);
  put16be(f, 12, 0x0800);
  f[14] = 0x45;
  put16be(f, 16, static_cast<std::uint16_t>(20 + ip_payload));
  f[22] = 64;
  f[23] = protocol;
  f[26] = 192; f[27] = 168; f[28] = 1; f[29] = 201;  // source 192.168.1.201
  f[30] = 255; f[31] = 255; f[32] = 255; f[33] = 255;
  return f;
}

}  // namespace

std::vector<std::uint8_t> udpFrame(std::uint16_t src_port, std::uint16_t dst_port,
                                   const std::vector<std::uint8_t>& payload) {
  auto f = ipv4Frame(17, 8 + payload.size());
  put16be(f, 34, src_port);
  put16be(f, 36, dst_port);
  put16be(f, 38, static_cast<std::uint16_t>(8 + payload.size()));
  std::copy(payload.begin(), payload.end(), f.begin() + 42);
  return f;
}

std::vector<std::uint8_t> tcpFrame() { return ipv4Frame(6, 40); }

std::vector<std::uint8_t> arpFrame() {
  std::vector<std::uint8_t> f(42, 0);
  put16be(f, 12, 0x0806);
  return f;
}

void writePcap(const std::string& path, const std::vector<PcapRecord>& records) {
  std::ofstream out(path, std::ios::binary);
  write32(out, 0xA1B2C3D4);
  out.put(2); out.put(0); out.put(4); out.put(0);  // version 2.4
  write32(out, 0);
  write32(out, 0);
  write32(out, 65535);
  write32(out, 1);  // Ethernet
  for (const auto& r : records) {
    write32(out, static_cast<std::uint32_t>(r.t_ns / 1'000'000'000));
    write32(out, static_cast<std::uint32_t>((r.t_ns % 1'000'000'000) / 1000));
    write32(out, static_cast<std::uint32_t>(r.frame.size()));
    write32(out, r.original_length ? r.original_length : static_cast<std::uint32_t>(r.frame.size()));
    out.write(reinterpret_cast<const char*>(r.frame.data()), static_cast<std::streamsize>(r.frame.size()));
  }
}

std::vector<std::uint8_t> vlp16Packet(std::uint32_t timestamp_us, int start_azimuth, int step,
                                      double distance_m, bool dual, double second_distance_m) {
  std::vector<std::uint8_t> p(1206, 0);
  for (int b = 0; b < 12; ++b) {
    const std::size_t at = static_cast<std::size_t>(b) * 100;
    p[at] = 0xFF;
    p[at + 1] = 0xEE;
    const int step_index = dual ? b / 2 : b;
    put16le(p, at + 2, static_cast<std::uint16_t>((start_azimuth + step_index * step) % 36000));
    const double d = dual && (b % 2 == 1) ? second_distance_m : distance_m;
    for (int c = 0; c < 32; ++c) {
      put16le(p, at + 4 + 3 * c, static_cast<std::uint16_t>(std::lround(d / 0.002)));
      p[at + 4 + 3 * c + 2] = static_cast<std::uint8_t>(10 + c);
    }
  }
  put32le(p, 1200, timestamp_us);
  p[1204] = dual ? 0x39 : 0x37;
  p[1205] = 0x22;
  return p;
}

std::vector<PcapRecord> vlp16Capture(double seconds, double hz, std::uint32_t t0_us, int azimuth0,
                                     std::int64_t record_offset_ns) {
  const double packet_us = 12 * 110.592;
  const double step = hz * 36000.0 * 110.592e-6;  // 0.01 deg per block
  std::vector<PcapRecord> records;
  const int packets = static_cast<int>(seconds * 1e6 / packet_us);
  for (int i = 0; i < packets; ++i) {
    const double t_us = t0_us + i * packet_us;
    const int azimuth = static_cast<int>(std::lround(azimuth0 + i * 12 * step)) % 36000;
    const auto sensor_us = static_cast<std::uint32_t>(std::llround(t_us)) % 3'600'000'000u;
    PcapRecord r;
    r.t_ns = record_offset_ns + static_cast<std::int64_t>(t_us * 1000.0);
    r.frame = udpFrame(2368, 2368, vlp16Packet(sensor_us, azimuth, static_cast<int>(std::lround(step))));
    records.push_back(std::move(r));
  }
  return records;
}

}  // namespace storey::test
