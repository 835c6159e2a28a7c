#pragma once
/// The back end with the SRP constraints off (`--no-srp`): keyframes by the
/// same rule as the SRP back end (keyframe_rule.h), every pose the odometry's.
#include "backend/backend.h"
#include "backend/keyframe_rule.h"

namespace storey {

class OdometryBackend : public Backend {
 public:
  explicit OdometryBackend(const KeyframeConfig& config) : selector_(config) {}
  /// The decision's pose is the scan levelled as the odometry knows it now;
  /// finish() levels every pose with the last levelling.
  BackendDecision addScan(double time, const Pose& T_odom_lidar,
                          const Eigen::Quaterniond& q_world_odom, const Scan& deskewed) override;
  SlamResult finish(const Scan& last_deskewed) override;

 private:
  KeyframeSelector selector_;
  Trajectory odometry_;                 ///< in the odometry's map frame
  std::vector<std::size_t> keyframes_;  ///< indices into odometry_
  Eigen::Quaterniond q_world_odom_ = Eigen::Quaterniond::Identity();  ///< the latest
  bool last_is_keyframe_ = false;
};

}  // namespace storey
