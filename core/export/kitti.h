#pragma once
/// Trajectories in the KITTI odometry format: one line per pose, the 12
/// numbers of the top 3x4 block of the 4x4 matrix T_world_lidar, row-major
/// (r11 r12 r13 tx r21 r22 r23 ty r31 r32 r33 tz), space-separated. KITTI
/// files hold no time: the times go to a second file, one per line [s], as
/// KITTI's times.txt. Frame: Storey's world frame (gravity-aligned, z up,
/// origin at the LiDAR's start), not KITTI's camera frame.
#include <string>

#include "trajectory/tum.h"

namespace storey {

/// Writes both files atomically; times_path may be empty (no times file).
void writeKitti(const std::string& poses_path, const std::string& times_path,
                const Trajectory& trajectory);

}  // namespace storey
