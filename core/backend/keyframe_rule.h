#pragma once
/// When a scan becomes a keyframe (the graph's vertices and the map's scans):
/// moved more than KeyframeConfig::distance, tilted more than
/// KeyframeConfig::pitch_roll_deg, or max_interval seconds since the last one.
/// The tilt is the angle between the world's up axis seen from the two poses
/// (the combined pitch and roll change, blind to yaw), so the rule is the same
/// for every sensor mounting and has no gimbal lock.
#include "backend/backend_config.h"
#include "types/pose.h"

namespace storey {

/// Angle between world z expressed in the frames of `T_world_a` and `T_world_b` [rad].
double tiltChange(const Pose& T_world_a, const Pose& T_world_b);

/// True when a scan at `T_world_now` (time `t_now` [s]) is a new keyframe
/// after the keyframe at `T_world_last` (time `t_last`).
bool isNewKeyframe(const KeyframeConfig& config, const Pose& T_world_last, double t_last,
                   const Pose& T_world_now, double t_now);

/// Keyframe selection for a stream of poses (the pipeline uses it when the
/// back end is off; the back end applies the same rule in its own frame).
class KeyframeSelector {
 public:
  explicit KeyframeSelector(const KeyframeConfig& config) : config_(config) {}
  /// True (and remembered as the last keyframe) when the pose is a new keyframe;
  /// the first pose always is.
  bool accept(const Pose& T_world_now, double t_now);

 private:
  KeyframeConfig config_;
  bool any_ = false;
  Pose T_world_last_;
  double t_last_ = 0.0;
};

}  // namespace storey
