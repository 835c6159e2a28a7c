#include "sim/velodyne_pcap_writer.h"

#include <cerrno>
#include <cmath>
#include <cstring>

#include "common/error.h"
#include "io/velodyne/velodyne_tables.h"

namespace storey::sim {
namespace {

namespace vd = velodyne;

constexpr std::size_t kBlockSize = 100;
constexpr std::size_t kEthernetHeader = 14, kIpv4Header = 20, kUdpHeader = 8;
constexpr std::size_t kPayloadOffset = kEthernetHeader + kIpv4Header + kUdpHeader;
constexpr std::size_t kFrameSize = kPayloadOffset + vd::kDataPacketSize;  // 1248
constexpr std::int64_t kHourUs = 3'600'000'000LL;
static_assert(VelodyneFiring::kMaxLasers == vd::kChannelsPerBlock, "block layout");
static_assert(4 + 3 * vd::kChannelsPerBlock == kBlockSize, "block size");

std::uint8_t productId(vd::Model model) {
  switch (model) {
    case vd::Model::kVlp16:
      return vd::kProductVlp16;
    case vd::Model::kVlp32c:
      return vd::kProductVlp32c;
    case vd::Model::kHdl32e:
      return vd::kProductHdl32e;
  }
  return vd::kProductVlp16;
}
static_assert(vd::kBlocksPerPacket * kBlockSize + 6 == vd::kDataPacketSize, "packet size");

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

/// Integer division rounding to nearest (halves up), for non-negative and negative n.
std::int64_t roundDiv(std::int64_t n, std::int64_t d) {
  return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

/// Azimuth in the packet's unit, 0..35999 [0.01 deg].
std::uint16_t azimuthField(double azimuth_deg) {
  long a = std::lround(azimuth_deg * 100.0) % 36000;
  if (a < 0) a += 36000;
  return static_cast<std::uint16_t>(a);
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
                                       double rotation_hz, velodyne::Model model)
    : path_(path),
      start_ns_(start_ns),
      rotation_hz_(rotation_hz),
      model_(model),
      lasers_(vd::laserCount(model)),
      sequences_per_block_(vd::kChannelsPerBlock / vd::laserCount(model)),
      period_ns_(std::llround(vd::sequencePeriod(model) * 1e9)) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) throw Error(path + ": cannot open for writing: " + std::strerror(errno));
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  pending_.reserve(vd::kBlocksPerPacket * sequences_per_block_);
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
  if (have_last_ && sequence.t_ns != last_.t_ns + period_ns_) {
    throw Error(path_ + ": firing sequence at " + std::to_string(sequence.t_ns) +
                " ns does not follow the one at " + std::to_string(last_.t_ns) + " ns by the " +
                vd::toString(model_) + "'s period of " + std::to_string(period_ns_) + " ns");
  }
  last_ = sequence;
  have_last_ = true;
  pending_.push_back(sequence);
  real_sequences_ = static_cast<int>(pending_.size());
  if (real_sequences_ == vd::kBlocksPerPacket * sequences_per_block_) writePacket();
}

void VelodynePcapWriter::writePacket() {
  std::uint8_t* payload = frame_.data() + kPayloadOffset;
  for (int b = 0; b < vd::kBlocksPerPacket; ++b) {
    std::uint8_t* block = payload + b * kBlockSize;
    put16le(block, vd::kBlockFlag);              // bytes 0xFF 0xEE
    const int first = sequences_per_block_ * b;  // the block's first sequence
    const std::uint16_t azimuth = azimuthField(pending_[first].azimuth_deg);
    put16le(block + 2, azimuth);
    if ((azimuth < last_block_azimuth_ || last_block_azimuth_ < 0) && first < real_sequences_) {
      frame_starts_.push_back(start_ns_ + pending_[first].t_ns);
    }
    last_block_azimuth_ = azimuth;
    for (int s = 0; s < sequences_per_block_; ++s) {
      const VelodyneFiring& q = pending_[first + s];
      for (int laser = 0; laser < lasers_; ++laser) {
        std::uint8_t* cell = block + 4 + 3 * (s * lasers_ + laser);
        put16le(cell, q.distance[laser]);
        cell[2] = q.reflectivity[laser];
      }
    }
  }
  // Timestamp: microseconds past the hour of the first firing of block 0.
  const std::int64_t first_ns = start_ns_ + pending_.front().t_ns;
  std::int64_t toh_us = roundDiv(first_ns, 1000) % kHourUs;
  if (toh_us < 0) toh_us += kHourUs;
  put32le(payload + 1200, static_cast<std::uint32_t>(toh_us));
  payload[1204] = static_cast<std::uint8_t>(vd::ReturnMode::kStrongest);  // 0x37
  payload[1205] = productId(model_);
  setIpv4IdAndChecksum(frame_.data() + kEthernetHeader, ip_id_++);

  // Record: the packet is complete after its sequences.
  const std::int64_t record_us =
      roundDiv(first_ns + vd::kBlocksPerPacket * sequences_per_block_ * period_ns_, 1000);
  std::uint8_t record[16];
  put32le(record, static_cast<std::uint32_t>(record_us / 1'000'000));
  put32le(record + 4, static_cast<std::uint32_t>(record_us % 1'000'000));
  put32le(record + 8, static_cast<std::uint32_t>(kFrameSize));
  put32le(record + 12, static_cast<std::uint32_t>(kFrameSize));
  writeBytes(record, sizeof(record));
  writeBytes(frame_.data(), frame_.size());
  ++packets_;
  pending_.clear();
  real_sequences_ = 0;
}

void VelodynePcapWriter::close() {
  if (file_ == nullptr) return;
  if (!pending_.empty()) {
    // The sensor keeps spinning: complete the packet with sequences without returns.
    const double step_deg = 360.0 * rotation_hz_ * period_ns_ * 1e-9;
    while (static_cast<int>(pending_.size()) < vd::kBlocksPerPacket * sequences_per_block_) {
      VelodyneFiring next;
      next.t_ns = last_.t_ns + period_ns_;
      next.azimuth_deg = std::fmod(last_.azimuth_deg + step_deg, 360.0);
      last_ = next;
      pending_.push_back(next);
    }
    writePacket();
  }
  const bool flushed = std::fflush(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) throw Error(path_ + ": cannot write: " + std::strerror(errno));
}

}  // namespace storey::sim
