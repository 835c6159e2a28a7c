#pragma once
/// Velodyne VLP-16 geometry and timing (VLP-16 user manual, rev. E, section 9):
/// 16 lasers fire one after another every 2.304 us in the order of their
/// laser ID; a firing sequence (16 firings + recharge) lasts 55.296 us. The
/// head spins clockwise seen from above. Ring = laser index sorted by
/// elevation (0 = -15 deg), as the ROS driver reports it.
///
/// The timing is the decoder's (io/velodyne/velodyne_tables.h), so what the
/// simulator fires is what a Velodyne capture of it decodes to; the
/// elevations are checked against the decoder's table by the tests.
#include <cmath>
#include <cstdint>

#include "io/velodyne/velodyne_tables.h"

namespace storey::sim::vlp16 {

constexpr int kLasers = 16;
/// Between consecutive lasers [ns] (2304).
constexpr std::int64_t kFiringIntervalNs =
    static_cast<std::int64_t>(velodyne::kVlp16FiringS * 1e9 + 0.5);
/// One firing sequence [ns] (55296).
constexpr std::int64_t kSequencePeriodNs =
    static_cast<std::int64_t>(velodyne::kVlp16SequenceS * 1e9 + 0.5);
static_assert(kFiringIntervalNs == 2304 && kSequencePeriodNs == 55296, "VLP-16 timing");

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

/// Distance unit of the sensor's packets and of the simulated ranges [m].
constexpr double kDistanceStep = 0.002;

}  // namespace storey::sim::vlp16
