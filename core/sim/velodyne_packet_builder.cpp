#include "sim/velodyne_packet_builder.h"

#include <cmath>

#include "common/error.h"
#include "io/velodyne/frame_assembler.h"

namespace storey::sim {
namespace {

namespace vd = velodyne;

constexpr std::size_t kBlockSize = 100;
constexpr std::int64_t kHourUs = 3'600'000'000LL;
static_assert(VelodyneFiring::kMaxLasers == vd::kChannelsPerBlock, "block layout");
static_assert(4 + 3 * vd::kChannelsPerBlock == kBlockSize, "block size");
static_assert(vd::kBlocksPerPacket * kBlockSize + 6 == vd::kDataPacketSize, "packet size");

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

}  // namespace

VelodynePacketBuilder::VelodynePacketBuilder(std::int64_t start_ns, double rotation_hz,
                                             velodyne::Model model, std::string context,
                                             int cut_azimuth)
    : start_ns_(start_ns),
      rotation_hz_(rotation_hz),
      model_(model),
      context_(std::move(context)),
      cut_azimuth_(cut_azimuth),
      lasers_(vd::laserCount(model)),
      sequences_per_block_(vd::kChannelsPerBlock / vd::laserCount(model)),
      period_ns_(std::llround(vd::sequencePeriod(model) * 1e9)) {
  pending_.reserve(vd::kBlocksPerPacket * sequences_per_block_);
}

double VelodynePacketBuilder::packetRate() const {
  return 1e9 / static_cast<double>(vd::kBlocksPerPacket * sequences_per_block_ * period_ns_);
}

bool VelodynePacketBuilder::add(const VelodyneFiring& sequence, BuiltPacket& out) {
  if (have_last_ && sequence.t_ns != last_.t_ns + period_ns_) {
    throw Error(context_ + ": firing sequence at " + std::to_string(sequence.t_ns) +
                " ns does not follow the one at " + std::to_string(last_.t_ns) + " ns by the " +
                vd::toString(model_) + "'s period of " + std::to_string(period_ns_) + " ns");
  }
  last_ = sequence;
  have_last_ = true;
  pending_.push_back(sequence);
  real_sequences_ = static_cast<int>(pending_.size());
  if (real_sequences_ < vd::kBlocksPerPacket * sequences_per_block_) return false;
  build(out);
  return true;
}

bool VelodynePacketBuilder::finish(BuiltPacket& out) {
  if (pending_.empty()) return false;
  // The sensor keeps spinning: complete the packet with sequences without returns.
  const double step_deg = 360.0 * rotation_hz_ * period_ns_ * 1e-9;
  while (static_cast<int>(pending_.size()) < vd::kBlocksPerPacket * sequences_per_block_) {
    VelodyneFiring next;
    next.t_ns = last_.t_ns + period_ns_;
    next.azimuth_deg = std::fmod(last_.azimuth_deg + step_deg, 360.0);
    last_ = next;
    pending_.push_back(next);
  }
  build(out);
  return true;
}

void VelodynePacketBuilder::build(BuiltPacket& out) {
  std::uint8_t* payload = out.payload.data();
  for (int b = 0; b < vd::kBlocksPerPacket; ++b) {
    std::uint8_t* block = payload + b * kBlockSize;
    put16le(block, vd::kBlockFlag);              // bytes 0xFF 0xEE
    const int first = sequences_per_block_ * b;  // the block's first sequence
    const std::uint16_t azimuth = azimuthField(pending_[first].azimuth_deg);
    put16le(block + 2, azimuth);
    const bool starts =
        last_block_azimuth_ < 0 || vd::startsFrame(last_block_azimuth_, azimuth, cut_azimuth_);
    if (starts && first < real_sequences_) {
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
  out.complete_ns =
      1000 * roundDiv(first_ns + vd::kBlocksPerPacket * sequences_per_block_ * period_ns_, 1000);
  ++packets_;
  pending_.clear();
  real_sequences_ = 0;
}

}  // namespace storey::sim
