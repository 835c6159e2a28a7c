#pragma once
/// Trajectories in the TUM RGB-D format: one line per pose,
/// `t x y z qx qy qz qw` (time in seconds, position in metres, unit
/// quaternion Hamilton x y z w); lines starting with '#' are comments.
#include <string>
#include <vector>

#include "types/pose.h"

namespace storey {

struct StampedPose {
  double time = 0.0;  ///< [s]
  Pose pose;
};
using Trajectory = std::vector<StampedPose>;

/// Writes atomically (temporary name, then rename); 9 decimals for time and
/// position, 9 for the quaternion.
void writeTum(const std::string& path, const Trajectory& trajectory);
/// Reads a TUM file; a malformed line is a storey::Error naming file and line.
/// Times must be strictly increasing.
Trajectory readTum(const std::string& path);

}  // namespace storey
