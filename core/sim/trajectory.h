#pragma once
/// The robot's body trajectory: a C4-smooth path (uniform quintic B-spline of
/// position, yaw, path pitch and gait weight sampled from a time-optimal walk
/// along the route) with a gait on top: a quadruped's trot (RobotMotion
/// kLegged) or a person's steps carrying the sensors by hand (kHandheld).
/// Everything is analytic: pose, velocity, acceleration and the rotation's
/// first and second derivatives.
/// Body frame: x forward, y left, z up; R_world_body = Rz(yaw) Ry(pitch) Rx(roll).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "sim/building.h"
#include "sim/building_spec.h"
#include "types/pose.h"

namespace storey::sim {

/// Kinematics of a rigid frame at one time, in the world frame unless named.
struct FrameKinematics {
  Pose T_world_frame;
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();      ///< [m/s]
  Eigen::Vector3d a_world = Eigen::Vector3d::Zero();      ///< [m/s^2]
  Eigen::Vector3d omega_frame = Eigen::Vector3d::Zero();  ///< angular rate in the frame [rad/s]
  Eigen::Matrix3d dR = Eigen::Matrix3d::Zero();           ///< d/dt R_world_frame
  Eigen::Matrix3d ddR = Eigen::Matrix3d::Zero();          ///< d2/dt2 R_world_frame
};

class Trajectory {
 public:
  /// Plans the walk along `route` (world frame) for `robot`. Stands still for
  /// robot.still_time at both ends; ends exactly where it started.
  Trajectory(const std::vector<RouteVertex>& route, const RobotSpec& robot);

  double duration() const { return duration_; }       ///< [s], t in [0, duration]
  double pathLength() const { return path_length_; }  ///< planned walking distance [m]
  double stillTime() const {
    return still_time_;
  }  ///< exactly still in [0, t] and [duration - t, duration]

  /// The body frame (t clamped to [0, duration]).
  FrameKinematics body(double t) const;
  Pose T_world_body(double t) const { return body(t).T_world_frame; }
  /// A frame rigidly mounted on the body (LiDAR, IMU): T_world_frame = T_world_body * T_body_frame.
  FrameKinematics frame(double t, const Pose& T_body_frame) const;

 private:
  static constexpr int kChannels = 6;  // x y z yaw pitch gait_weight
  using Channels = Eigen::Matrix<double, kChannels, 1>;
  /// Value, first and second time derivative of the B-spline channels.
  void evalSpline(double t, Channels& c, Channels& dc, Channels& ddc) const;
  FrameKinematics legged(double t, const Channels& c, const Channels& dc,
                         const Channels& ddc) const;
  FrameKinematics handheld(double t, const Channels& c, const Channels& dc,
                           const Channels& ddc) const;

  std::vector<Channels> control_;  ///< control point k peaks at time (k - 2) * dt_
  double dt_ = 0.05;
  double duration_ = 0.0;
  double path_length_ = 0.0;
  double still_time_ = 0.0;
  RobotMotion motion_ = RobotMotion::kLegged;
  GaitSpec gait_;
  HandheldGaitSpec handheld_gait_;
};

/// Specific force measured by an accelerometer on this frame: R^T (a - g_world),
/// g_world = (0, 0, -gravity).
Eigen::Vector3d specificForce(const FrameKinematics& k, double gravity);

}  // namespace storey::sim
