#include "sim/velodyne_pcap_writer.h"

#include <cerrno>
#include <cmath>
#include <cstring>

#include "common/error.h"
#include "io/velodyne/velodyne_tables.h"

namespace storey::sim {
namespace {

namespace vd = velodyne;

constexpr std::size_t kEthernetHeader = 14, kIpv4Header = 20, kUdpHeader = 8;
constexpr std::size_t kPayloadOffset = kEthernetHeader + kIpv4Header + kUdpHeader;
constexpr std::size_t kFrameSize = kPayloadOffset + vd::kDataPacketSize;  // 1248

void put16be(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 8);
  p[1] = static_cast<std::uint8_t>(v);
}
void put16le(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put32le(std::uint8_t* p, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) p[k] = static_cast<std::uint8_t>(v >> (8 * k));
}

/// The Ethernet + IPv4 + UDP headers of a VLP-16 data packet (the checksum
/// and id are set per packet).
void initFrame(std::vector<std::uint8_t>& f) {
  f.assign(kFrameSize, 0);
  std::uint8_t* eth = f.data();
  std::memset(eth, 0xFF, 6);                                                // broadcast
  const std::uint8_t source_mac[6] = {0x60, 0x76, 0x88, 0x00, 0x00, 0x01};  // Velodyne OUI
  std::memcpy(eth + 6, source_mac, 6);
  put16be(eth + 12, 0x0800);  // IPv4
  std::uint8_t* ip = eth + kEthernetHeader;
  ip[0] = 0x45;
  put16be(ip + 2, static_cast<std::uint16_t>(kIpv4Header + kUdpHeader + vd::kDataPacketSize));
  put16be(ip + 6, 0x4000);                               // don't fragment
  ip[8] = 64;                                            // TTL
  ip[9] = 17;                                            // UDP
  const std::uint8_t source_ip[4] = {192, 168, 1, 201};  // the sensor's factory address
  std::memcpy(ip + 12, source_ip, 4);
  std::memset(ip + 16, 0xFF, 4);
  std::uint8_t* udp = ip + kIpv4Header;
  put16be(udp, vd::kDefaultDataPort);
  put16be(udp + 2, vd::kDefaultDataPort);
  put16be(udp + 4, static_cast<std::uint16_t>(kUdpHeader + vd::kDataPacketSize));
  // UDP checksum 0: none (allowed over IPv4).
}

void setIpv4IdAndChecksum(std::uint8_t* ip, std::uint16_t id) {
  put16be(ip + 4, id);
  put16be(ip + 10, 0);
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < kIpv4Header; i += 2) sum += (ip[i] << 8) | ip[i + 1];
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  put16be(ip + 10, static_cast<std::uint16_t>(~sum));
}

}  // namespace

VelodynePcapWriter::VelodynePcapWriter(const std::string& path, std::int64_t start_ns,
                                       double rotation_hz, velodyne::Model model, int cut_azimuth)
    : path_(path), builder_(start_ns, rotation_hz, model, path, cut_azimuth) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) throw Error(path + ": cannot open for writing: " + std::strerror(errno));
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  initFrame(frame_);
  // Classic pcap header: little-endian, microsecond stamps, version 2.4, Ethernet.
  std::uint8_t header[24] = {};
  put32le(header, 0xA1B2C3D4);
  put16le(header + 4, 2);
  put16le(header + 6, 4);
  put32le(header + 16, 65535);  // snap length
  put32le(header + 20, 1);      // LINKTYPE_ETHERNET
  writeBytes(header, sizeof(header));
}

VelodynePcapWriter::~VelodynePcapWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void VelodynePcapWriter::writeBytes(const void* data, std::size_t size) {
  if (std::fwrite(data, 1, size, file_) != size)
    throw Error(path_ + ": cannot write: " + std::strerror(errno));
  bytes_ += size;
}

void VelodynePcapWriter::add(const VelodyneFiring& sequence) {
  if (file_ == nullptr) throw Error(path_ + ": the capture is already closed");
  if (builder_.add(sequence, packet_)) writePacket();
}

void VelodynePcapWriter::writePacket() {
  std::memcpy(frame_.data() + kPayloadOffset, packet_.payload.data(), packet_.payload.size());
  setIpv4IdAndChecksum(frame_.data() + kEthernetHeader, ip_id_++);
  // Record: the packet is complete after its sequences.
  const std::int64_t record_us = packet_.complete_ns / 1000;
  std::uint8_t record[16];
  put32le(record, static_cast<std::uint32_t>(record_us / 1'000'000));
  put32le(record + 4, static_cast<std::uint32_t>(record_us % 1'000'000));
  put32le(record + 8, static_cast<std::uint32_t>(kFrameSize));
  put32le(record + 12, static_cast<std::uint32_t>(kFrameSize));
  writeBytes(record, sizeof(record));
  writeBytes(frame_.data(), frame_.size());
}

void VelodynePcapWriter::close() {
  if (file_ == nullptr) return;
  if (builder_.finish(packet_)) writePacket();
  const bool flushed = std::fflush(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) throw Error(path_ + ": cannot write: " + std::strerror(errno));
}

}  // namespace storey::sim
