#pragma once
// Small helpers of the evaluation tests: temporary folders, files, trajectories.
#include <string>

#include "trajectory/tum.h"

namespace storey::test::eval {

/// A fresh folder under the system's temporary directory.
std::string makeTempDir(const std::string& name);
void writeText(const std::string& path, const std::string& text);
std::string readText(const std::string& path);

/// Pose with a rotation of `yaw` about z [rad] at position p.
Pose yawPose(double yaw, const Eigen::Vector3d& p);

/// A walk of `n` poses at 10 Hz from time t0: a rectangle-ish path with
/// heading changes, climbing in z, with varying roll and pitch (not planar, so
/// that an alignment is fully determined).
Trajectory wigglyWalk(int n, double t0 = 100.0);

}  // namespace storey::test::eval
