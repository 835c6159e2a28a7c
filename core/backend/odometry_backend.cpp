#include "backend/odometry_backend.h"

namespace storey {

BackendDecision OdometryBackend::addScan(double time, const Pose& T_odom_lidar,
                                         const Eigen::Quaterniond& q_world_odom, const Scan&) {
  odometry_.push_back({time, T_odom_lidar});
  q_world_odom_ = q_world_odom;
  const Pose T_world_lidar = Pose(q_world_odom, Eigen::Vector3d::Zero()) * T_odom_lidar;
  last_is_keyframe_ = selector_.accept(T_world_lidar, time);
  if (last_is_keyframe_) keyframes_.push_back(odometry_.size() - 1);
  return {last_is_keyframe_, T_world_lidar};
}

SlamResult OdometryBackend::finish(const Scan&) {
  if (!last_is_keyframe_ && !odometry_.empty()) keyframes_.push_back(odometry_.size() - 1);
  last_is_keyframe_ = true;
  // One levelling, the odometry's last (best) gravity estimate, for every pose.
  const Pose T_world_odom(q_world_odom_, Eigen::Vector3d::Zero());
  SlamResult result;
  result.odometry.reserve(odometry_.size());
  for (const StampedPose& p : odometry_) result.odometry.push_back({p.time, T_world_odom * p.pose});
  result.trajectory = result.odometry;
  for (std::size_t k : keyframes_) result.keyframes.push_back(result.odometry[k]);
  return result;
}

}  // namespace storey
