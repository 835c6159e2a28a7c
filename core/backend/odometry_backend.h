#pragma once
/// The back end with the SRP constraints off (`--no-srp`): keyframes by the
/// same rule as the SRP back end (keyframe_rule.h), every pose the odometry's.
#include "backend/backend.h"
#include "backend/keyframe_rule.h"

namespace storey {

class OdometryBackend : public Backend {
 public:
  explicit OdometryBackend(const KeyframeConfig& config) : selector_(config) {}
  BackendDecision addScan(double time, const Pose& T_world_lidar, const Scan& deskewed) override;
  SlamResult finish() override;

 private:
  KeyframeSelector selector_;
  SlamResult result_;
  bool last_is_keyframe_ = false;
};

}  // namespace storey
