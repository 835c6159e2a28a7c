#pragma once
/// Velodyne VLP-16 geometry and timing (VLP-16 user manual, rev. E, section 9):
/// 16 lasers fire one after another every 2.304 us in the order of their
/// laser ID; a firing sequence (16 firings + recharge) lasts 55.296 us. The
/// head spins clockwise seen from above. Ring = laser index sorted by
/// elevation (0 = -15 deg), as the ROS driver reports it.
#include <cmath>
#include <cstdint>

namespace storey::sim::vlp16 {

constexpr int kLasers = 16;
constexpr std::int64_t kFiringIntervalNs = 2304;   ///< between consecutive lasers [ns]
constexpr std::int64_t kSequencePeriodNs = 55296;  ///< one firing sequence [ns]

/// Elevation of laser `id` (firing order) [deg]: -15, 1, -13, 3, ..., -1, 15.
constexpr int elevationDeg(int id) {
  return (id % 2 == 0) ? -15 + id : id;
}
inline double elevation(int id) {
  return elevationDeg(id) * M_PI / 180.0;
}
/// Ring number of laser `id`: 0 = lowest beam (-15 deg) ... 15 = highest (+15 deg).
constexpr int ring(int id) {
  return (elevationDeg(id) + 15) / 2;
}

}  // namespace storey::sim::vlp16
