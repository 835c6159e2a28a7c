#pragma once
/// The SRP back end (section V of the reference paper, docs/method/backend.md):
/// keyframes from the odometry, structural representative planes of each
/// keyframe's deskewed scan, their association with the global plane map, and
/// the keyframe graph (odometry relative poses + plane observations) solved
/// with Ceres whenever a plane constraint appears. The odometry is left
/// alone: the back end keeps the graph's latest correction of the odometry's
/// frame (T_world_odom) and applies it to the poses it returns; at the end
/// every scan's pose is its odometry pose corrected by interpolating the
/// corrections of the keyframes around it.
#include <memory>

#include "backend/backend.h"

namespace storey {

class SrpBackend : public Backend {
 public:
  explicit SrpBackend(const BackendConfig& config);
  ~SrpBackend() override;
  SrpBackend(const SrpBackend&) = delete;
  SrpBackend& operator=(const SrpBackend&) = delete;

  /// `T_odom_lidar`: the odometry's pose (in the odometry's own rigid map
  /// frame); relative poses come from it. `q_world_odom`: the odometry's
  /// current levelling of that frame: it starts the graph's world levelled
  /// and sets the first keyframe's roll/pitch prior at every solve, so a
  /// better gravity estimate turns the whole graph (docs/method/backend.md).
  /// The decision's pose is the scan moved by the corrections of the solves
  /// so far (before this scan's own solve, when it is a keyframe that
  /// triggers one).
  BackendDecision addScan(double time, const Pose& T_odom_lidar,
                          const Eigen::Quaterniond& q_world_odom, const Scan& deskewed) override;
  /// The last scan as a keyframe, the final whole-graph solve and the
  /// wrong-association count. Call once.
  SlamResult finish(const Scan& last_deskewed) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace storey
