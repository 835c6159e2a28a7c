#include "trajectory/drift.h"

#include <algorithm>
#include <cmath>

namespace storey {

double pathLength(const Trajectory& trajectory) {
  double length = 0.0;
  for (std::size_t i = 1; i < trajectory.size(); ++i)
    length += (trajectory[i].pose.translation() - trajectory[i - 1].pose.translation()).norm();
  return length;
}

EndPointDrift endPointDrift(const Trajectory& trajectory) {
  EndPointDrift drift;
  if (trajectory.size() < 2) return drift;
  const Pose T_start_end = trajectory.front().pose.inverse() * trajectory.back().pose;
  const Eigen::Vector3d& t = T_start_end.translation();
  drift.dx = t.x();
  drift.dy = t.y();
  drift.dz = t.z();
  drift.dxyz = t.norm();
  const Eigen::Matrix3d R = T_start_end.rotationMatrix();
  drift.dyaw = std::atan2(R(1, 0), R(0, 0));
  drift.dpitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  drift.droll = std::atan2(R(2, 1), R(2, 2));
  drift.dangle = T_start_end.angle();
  drift.path_length = pathLength(trajectory);
  return drift;
}

}  // namespace storey
