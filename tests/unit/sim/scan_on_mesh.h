#pragma once
/// Test helper: how far a simulated scan's points are from the true mesh.
#include <algorithm>
#include <cstddef>

#include "sim/world.h"
#include "types/scan.h"

namespace storey::sim {

/// The largest distance to the building's mesh of every `stride`-th point of
/// `scan` (stamp relative to the start of the simulation), each placed with
/// the LiDAR's true pose at its own firing time [m].
inline double worstDistanceToMesh(const World& world, const Scan& scan, const Pose& T_body_lidar,
                                  std::size_t stride) {
  double worst = 0.0;
  for (std::size_t i = 0; i < scan.points.size(); i += stride) {
    const ScanPoint& p = scan.points[i];
    const Pose T_world_lidar =
        world.trajectory.frame(scan.stamp_ns * 1e-9 + p.time, T_body_lidar).T_world_frame;
    worst = std::max(worst, world.building.mesh.distanceTo(T_world_lidar * p.p.cast<double>()));
  }
  return worst;
}

}  // namespace storey::sim
