#pragma once
/// End-point drift, the paper's Table I: when a recording starts and ends at
/// the same place, the estimated end pose relative to the start pose is the
/// accumulated error. Translation in the start frame's axes; angles as
/// yaw-pitch-roll (ZYX) of the relative rotation.
#include "trajectory/tum.h"

namespace storey {

struct EndPointDrift {
  double dx = 0, dy = 0, dz = 0, dxyz = 0;              ///< [m]
  double dyaw = 0, dpitch = 0, droll = 0, dangle = 0;  ///< [rad]
  double path_length = 0;                               ///< [m]
  double percent_of_path() const { return path_length > 0 ? 100.0 * dxyz / path_length : 0.0; }
};

/// Drift of the last pose relative to the first (empty trajectory: all zero).
EndPointDrift endPointDrift(const Trajectory& trajectory);
/// Sum of the distances between consecutive positions [m].
double pathLength(const Trajectory& trajectory);

}  // namespace storey
