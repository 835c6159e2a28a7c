#include "io/velodyne/velodyne_packet.h"

#include <cmath>
#include <cstring>

namespace storey::velodyne {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr std::size_t kBlockSize = 100;
constexpr std::size_t kTimestampOffset = 1200;
/// A block-to-block azimuth step above this is a glitch, not rotation [0.01 deg].
constexpr int kMaxPlausibleStep = 500;

std::uint16_t u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
std::uint32_t u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
/// 12-bit two's complement in the low bits of a little-endian uint16.
int s12(const std::uint8_t* p) {
  const int raw = u16(p) & 0x0FFF;
  return raw >= 0x800 ? raw - 0x1000 : raw;
}

/// nebula's block azimuths and rotations (see AzimuthInterpolation::kNebula): block b starts
/// from the azimuth its predecessor looked ahead to (block b + 1 in dual return mode) and
/// rotates by the difference to the block 1 (single) or 2 (dual) further on; without one, by
/// the last difference, or by nothing in the packet's last block (nebula's VLP-32 decoder sets
/// that block 4 earlier in dual return mode, a block that always has a successor).
void nebulaBlockAzimuths(const std::array<std::uint16_t, kBlocksPerPacket>& sent, bool dual,
                         bool vlp16, std::array<int, kBlocksPerPacket>& base,
                         std::array<int, kBlocksPerPacket>& rotation) {
  const int ahead = dual ? 2 : 1;
  const int unrotated = kBlocksPerPacket - 1 - (dual ? (vlp16 ? 1 : 4) : 0);
  int next = 0;
  int last = 0;
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    base[b] = b == 0 ? sent[0] : next;
    if (b < kBlocksPerPacket - ahead) {
      next = sent[b + ahead];
      last = (36000 + next - base[b]) % 36000;
      rotation[b] = last;
    } else {
      rotation[b] = b == unrotated ? 0 : last;
    }
  }
}

}  // namespace

bool AzimuthWindow::contains(double azimuth) const {
  const double lo = min_deg * 100.0;
  const double hi = max_deg * 100.0;
  return min_deg <= max_deg ? azimuth >= lo && azimuth <= hi : azimuth <= hi || azimuth >= lo;
}

const char* toString(PacketProblem problem) {
  switch (problem) {
    case PacketProblem::kNone:
      return "ok";
    case PacketProblem::kWrongSize:
      return "velodyne_packet_wrong_size";
    case PacketProblem::kBadBlockFlag:
      return "velodyne_packet_bad_block_flag";
    case PacketProblem::kBadAzimuth:
      return "velodyne_packet_bad_azimuth";
    case PacketProblem::kUnknownReturnMode:
      return "velodyne_packet_unknown_return_mode";
  }
  return "unknown";
}

bool peekDataPacket(const std::uint8_t* data, std::size_t size, std::uint32_t& timestamp_us,
                    std::uint8_t& return_mode, std::uint8_t& product) {
  if (size != kDataPacketSize) return false;
  timestamp_us = u32(data + kTimestampOffset);
  return_mode = data[1204];
  product = data[1205];
  return true;
}

PacketDecoder::PacketDecoder(Calibration calibration, DecodeOptions options)
    : calibration_(std::move(calibration)), options_(options) {
  for (const auto& laser : calibration_.lasers) {
    cos_el_.push_back(std::cos(laser.elevation_deg * kDegToRad));
    sin_el_.push_back(std::sin(laser.elevation_deg * kDegToRad));
  }
}

double PacketDecoder::firingOffset(int block, int sequence, int laser, bool dual) const {
  const int step = dual ? block / 2 : block;  // both blocks of a dual pair are one firing
  const Model model = calibration_.model;
  const int sequences_per_block = model == Model::kVlp16 ? 2 : 1;
  return (sequences_per_block * step + sequence) * sequencePeriod(model) +
         laserFiringOffset(model, laser);
}

PacketProblem PacketDecoder::decode(const std::uint8_t* data, std::size_t size,
                                    DataPacket& packet) const {
  packet.returns.clear();
  packet.counts = PacketCounts{};
  if (size != kDataPacketSize) return PacketProblem::kWrongSize;
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const std::uint8_t* block = data + b * kBlockSize;
    if (u16(block) != kBlockFlag) return PacketProblem::kBadBlockFlag;
    packet.block_azimuth[b] = u16(block + 2);
    if (packet.block_azimuth[b] > 36000) return PacketProblem::kBadAzimuth;  // 36000 = 0 (sent so)
  }
  packet.timestamp_us = u32(data + kTimestampOffset);
  packet.return_mode = data[1204];
  packet.product = data[1205];
  const bool dual = packet.dual();
  if (packet.return_mode != 0 && packet.return_mode != 0x37 && packet.return_mode != 0x38 &&
      !dual) {
    return PacketProblem::kUnknownReturnMode;
  }

  const bool vlp16 = calibration_.model == Model::kVlp16;
  const int lasers = laserCount(calibration_.model);
  const int sequences = vlp16 ? 2 : 1;
  const int blocks_per_step = dual ? 2 : 1;
  const bool nebula = options_.azimuth == AzimuthInterpolation::kNebula;
  // Per block: the azimuth the lasers' rotation starts from and the rotation
  // over one firing step (one or two blocks) [0.01 deg].
  std::array<int, kBlocksPerPacket> base{};
  std::array<int, kBlocksPerPacket> rotation{};
  if (nebula) {
    nebulaBlockAzimuths(packet.block_azimuth, dual, vlp16, base, rotation);
  } else {
    // From the next step's azimuth; the last step repeats the previous one's.
    const int steps = kBlocksPerPacket / blocks_per_step;
    std::array<int, kBlocksPerPacket> step_rotation{};
    for (int s = 0; s < steps; ++s) {
      const int here = packet.block_azimuth[s * blocks_per_step];
      int d;
      if (s + 1 < steps) {
        d = (packet.block_azimuth[(s + 1) * blocks_per_step] - here + 36000) % 36000;
      } else {
        d = s > 0 ? step_rotation[s - 1] : 0;
      }
      if (d > kMaxPlausibleStep) d = s > 0 ? step_rotation[s - 1] : 0;
      step_rotation[s] = d;
    }
    for (int b = 0; b < kBlocksPerPacket; ++b) {
      base[b] = packet.block_azimuth[b];
      rotation[b] = step_rotation[b / blocks_per_step];
    }
  }
  const double step_duration = sequences * sequencePeriod(calibration_.model);
  const double resolution = calibration_.distance_resolution_m;
  const AzimuthWindow& window = options_.window;

  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const std::uint8_t* block = data + b * kBlockSize;
    const int step = b / blocks_per_step;
    const bool second = dual && (b % 2 == 1);
    // nebula's VLP-16 decoder tests its own block azimuth (only when min < max).
    const bool block_outside =
        !window.all() &&
        (nebula && vlp16 ? window.min_deg < window.max_deg && !window.contains(base[b])
                         : !window.contains(packet.block_azimuth[b]));
    for (int seq = 0; seq < sequences; ++seq) {
      for (int laser = 0; laser < lasers; ++laser) {
        const int channel = seq * lasers + laser;
        const std::uint8_t* cell = block + 4 + 3 * channel;
        const std::uint16_t raw = u16(cell);
        if (raw == 0) {
          ++packet.counts.no_return;
          continue;
        }
        if (second && u16(cell - kBlockSize) == raw && options_.drop_identical_second_return) {
          ++packet.counts.identical_second;
          continue;
        }
        const Laser& cal = calibration_.lasers[laser];
        const double distance = raw * resolution + cal.distance_offset_m;
        const bool in_range =
            nebula ? distance > options_.min_range && distance < options_.max_range
                   : distance >= options_.min_range && distance <= options_.max_range;
        if (!in_range) {
          ++packet.counts.out_of_range;
          continue;
        }
        if (block_outside) {
          ++packet.counts.outside_window;
          continue;
        }
        const double offset = firingOffset(b, seq, laser, dual);
        double azimuth_deg;
        if (nebula) {
          // VLP-16: (laser x 2.304 + sequence x 55.296) / 110.592 = (laser + 24 sequence) / 48;
          // 32-laser models: channel x 2.304 / 55.296 = channel / 24 (exact, for the rounding).
          const int numerator = vlp16 ? laser + 24 * seq : channel;
          const int denominator = vlp16 ? 48 : 24;
          double azimuth_cdeg = base[b] +
                                static_cast<double>(rotation[b] * numerator) / denominator -
                                cal.azimuth_offset_deg * 100.0;
          azimuth_cdeg -= 36000.0 * std::floor(azimuth_cdeg / 36000.0);
          // Nearest 0.01 deg, halves up (the margin absorbs the offset's binary rounding).
          azimuth_cdeg = std::fmod(std::floor(azimuth_cdeg + 0.5 + 1e-6), 36000.0);
          if (vlp16 && !window.all() && !window.contains(azimuth_cdeg)) {
            ++packet.counts.outside_window;
            continue;
          }
          azimuth_deg = azimuth_cdeg * 0.01;
        } else {
          const double within_step = offset - step * step_duration;  // time since the step began
          const double fraction = options_.azimuth == AzimuthInterpolation::kPerLaser
                                      ? within_step / step_duration
                                      : static_cast<double>(seq) / sequences;
          azimuth_deg = (base[b] + rotation[b] * fraction) * 0.01 - cal.azimuth_offset_deg;
        }
        azimuth_deg -= 360.0 * std::floor(azimuth_deg / 360.0);
        const double az = azimuth_deg * kDegToRad;
        const double horizontal = distance * cos_el_[laser];
        Return r;
        r.x = static_cast<float>(horizontal * std::cos(az));
        r.y = static_cast<float>(-horizontal * std::sin(az));
        r.z = static_cast<float>(distance * sin_el_[laser]);
        r.distance = static_cast<float>(distance);
        r.azimuth_deg = static_cast<float>(azimuth_deg);
        r.time_offset_s = offset;
        r.intensity = cell[2];
        r.laser = static_cast<std::uint8_t>(laser);
        r.block = static_cast<std::uint8_t>(b);
        r.sequence = static_cast<std::uint8_t>(seq);
        r.ring = cal.ring;
        r.second_return = second;
        packet.returns.push_back(r);
      }
    }
  }
  return PacketProblem::kNone;
}

bool decodePositionPacket(const std::uint8_t* data, std::size_t size, PositionPacket& packet) {
  if (size != kPositionPacketSize) return false;
  constexpr double kGyroDpsPerLsb = 0.09766;
  constexpr double kTempCPerLsb = 0.1453;
  constexpr double kAccelGPerLsb = 0.001221;
  for (int board = 0; board < 3; ++board) {
    const std::uint8_t* p = data + 14 + 8 * board;
    packet.gyro_dps[board] = s12(p) * kGyroDpsPerLsb;
    packet.temp_c[board] = s12(p + 2) * kTempCPerLsb + 25.0;
    packet.accel_g[2 * board] = s12(p + 4) * kAccelGPerLsb;
    packet.accel_g[2 * board + 1] = s12(p + 6) * kAccelGPerLsb;
  }
  packet.timestamp_us = u32(data + 198);
  packet.has_nmea = std::memcmp(data + 206, "$GP", 3) == 0;
  return true;
}

}  // namespace storey::velodyne
