#include "backend/odometry_backend.h"

namespace storey {

BackendDecision OdometryBackend::addScan(double time, const Pose& T_world_lidar, const Scan&) {
  const StampedPose stamped{time, T_world_lidar};
  result_.odometry.push_back(stamped);
  result_.trajectory.push_back(stamped);
  last_is_keyframe_ = selector_.accept(T_world_lidar, time);
  if (last_is_keyframe_) result_.keyframes.push_back(stamped);
  return {last_is_keyframe_, T_world_lidar};
}

SlamResult OdometryBackend::finish() {
  if (!last_is_keyframe_ && !result_.trajectory.empty())
    result_.keyframes.push_back(result_.trajectory.back());
  last_is_keyframe_ = true;
  return std::move(result_);
}

}  // namespace storey
