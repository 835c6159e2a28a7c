#pragma once
/// Packs Velodyne firing sequences into data packets as the sensor sends
/// them (single return "strongest"): 1206-byte payloads of 12 blocks of 100
/// bytes (flag 0xFF 0xEE, azimuth of the block's first firing in 0.01 deg,
/// then 32 x (distance, reflectivity): a VLP-16 block holds 2 firing
/// sequences x 16 lasers, a VLP-32C or HDL-32E block one sequence of 32), the
/// timestamp (uint32, microseconds past the hour of the first firing of block
/// 0), return mode 0x37 and the product id (VLP-16 0x22, VLP-32C 0x28,
/// HDL-32E 0x21). The capture writer and the VelodyneScan messages share it.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/velodyne/velodyne_tables.h"
#include "sim/velodyne_firing.h"

namespace storey::sim {

struct BuiltPacket {
  std::array<std::uint8_t, velodyne::kDataPacketSize> payload{};
  /// When the packet is complete (its first firing + its sequences' span),
  /// rounded to the microsecond: its record (receipt) time [ns, absolute].
  std::int64_t complete_ns = 0;
};

class VelodynePacketBuilder {
 public:
  /// `start_ns`: the absolute time of VelodyneFiring::t_ns = 0; `rotation_hz`
  /// continues the azimuth over the no-return sequences that fill the last
  /// packet; `context` names the output in errors; `cut_azimuth` [0.01 deg] is
  /// where a reader cuts frames (frameStarts; velodyne::cutAzimuth).
  VelodynePacketBuilder(std::int64_t start_ns, double rotation_hz, velodyne::Model model,
                        std::string context, int cut_azimuth = 0);

  /// Adds the next firing sequence (it must follow the last one at the
  /// model's period, else storey::Error); true when `out` received a packet.
  bool add(const VelodyneFiring& sequence, BuiltPacket& out);
  /// Completes the last packet with no-return sequences; true when there was one.
  bool finish(BuiltPacket& out);

  std::int64_t packets() const { return packets_; }
  /// Absolute times of the first firing of the blocks that start a frame
  /// when Storey's reader cuts the packets at `cut_azimuth` (velodyne::
  /// startsFrame; cut 0: as VeloView, where the azimuth wraps): the first
  /// block, then every block that passes the cut [ns]. Blocks of the
  /// sequences finish() adds are left out.
  const std::vector<std::int64_t>& frameStarts() const { return frame_starts_; }
  velodyne::Model model() const { return model_; }
  /// Data packets per second.
  double packetRate() const;

 private:
  void build(BuiltPacket& out);

  std::int64_t start_ns_;
  double rotation_hz_;
  velodyne::Model model_;
  std::string context_;
  int cut_azimuth_;                      ///< [0.01 deg]
  int lasers_;                           ///< per firing sequence
  int sequences_per_block_;              ///< 2 (VLP-16) or 1
  std::int64_t period_ns_;               ///< between firing sequences
  std::vector<VelodyneFiring> pending_;  ///< sequences of the packet being filled
  bool have_last_ = false;
  VelodyneFiring last_;
  std::int64_t packets_ = 0;
  int real_sequences_ = 0;  ///< of pending_, the ones added (not filling up the last packet)
  int last_block_azimuth_ = -1;
  std::vector<std::int64_t> frame_starts_;
};

}  // namespace storey::sim
