#pragma once
/// One firing sequence as a Velodyne sensor reports it in its data packets
/// (half a VLP-16 block, a whole VLP-32C or HDL-32E block): the raw returns of
/// its lasers, no-returns included. The LiDAR simulator fills them for the
/// capture writer (sim/velodyne_pcap_writer.h).
#include <array>
#include <cstdint>

namespace storey::sim {

struct VelodyneFiring {
  static constexpr int kMaxLasers = 32;
  std::int64_t t_ns = 0;     ///< time of its first firing (laser 0) [ns]
  double azimuth_deg = 0.0;  ///< head azimuth at that time [deg], in [0, 360)
  /// By laser id, in the model's distance steps (2 mm; VLP-32C 4 mm); 0 = no return.
  std::array<std::uint16_t, kMaxLasers> distance{};
  std::array<std::uint8_t, kMaxLasers> reflectivity{};  ///< by laser id [0, 255]
};

}  // namespace storey::sim
