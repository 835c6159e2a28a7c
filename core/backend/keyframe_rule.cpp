#include "backend/keyframe_rule.h"

#include <algorithm>
#include <cmath>

namespace storey {

double tiltChange(const Pose& T_world_a, const Pose& T_world_b) {
  const Eigen::Vector3d up_a = T_world_a.rotation().conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_b = T_world_b.rotation().conjugate() * Eigen::Vector3d::UnitZ();
  return std::atan2(up_a.cross(up_b).norm(), up_a.dot(up_b));
}

bool isNewKeyframe(const KeyframeConfig& config, const Pose& T_world_last, double t_last,
                   const Pose& T_world_now, double t_now) {
  if (config.max_interval > 0 && t_now - t_last >= config.max_interval) return true;
  if ((T_world_now.translation() - T_world_last.translation()).norm() > config.distance)
    return true;
  return tiltChange(T_world_last, T_world_now) > config.pitch_roll_deg * M_PI / 180.0;
}

bool KeyframeSelector::accept(const Pose& T_world_now, double t_now) {
  if (any_ && !isNewKeyframe(config_, T_world_last_, t_last_, T_world_now, t_now)) return false;
  any_ = true;
  T_world_last_ = T_world_now;
  t_last_ = t_now;
  return true;
}

}  // namespace storey
