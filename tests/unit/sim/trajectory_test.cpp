#include "sim/trajectory.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/world.h"

namespace storey::sim {
namespace {

const World& defaultWorld() {
  static const World world = makeWorld(loadBuildingSpec("default"));
  return world;
}

Eigen::Vector3d rotationLog(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

TEST(SimTrajectory, DerivativesMatchFiniteDifferences) {
  const Trajectory& traj = defaultWorld().trajectory;
  const Pose T_body_lidar(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
      Eigen::Vector3d(0.25, -0.05, 0.12));
  const double h = 1e-4;
  int checked = 0;
  for (double t = 1.0; t < traj.duration() - 1.0; t += 0.37) {
    const FrameKinematics k = traj.frame(t, T_body_lidar);
    const FrameKinematics kp = traj.frame(t + h, T_body_lidar);
    const FrameKinematics km = traj.frame(t - h, T_body_lidar);
    const Eigen::Vector3d p = k.T_world_frame.translation();
    const Eigen::Vector3d v_fd =
        (kp.T_world_frame.translation() - km.T_world_frame.translation()) / (2 * h);
    const Eigen::Vector3d a_fd =
        (kp.T_world_frame.translation() - 2 * p + km.T_world_frame.translation()) / (h * h);
    EXPECT_LT((k.v_world - v_fd).norm(), 1e-6) << "t=" << t;
    EXPECT_LT((k.a_world - a_fd).norm(), 2e-3) << "t=" << t;
    EXPECT_LT((k.a_world - (kp.v_world - km.v_world) / (2 * h)).norm(), 1e-5) << "t=" << t;
    // Angular rate in the frame: log(R(t-h)^T R(t+h)) / 2h.
    const Eigen::Matrix3d R = k.T_world_frame.rotationMatrix();
    const Eigen::Vector3d w_fd = rotationLog(km.T_world_frame.rotationMatrix().transpose() *
                                             kp.T_world_frame.rotationMatrix()) /
                                 (2 * h);
    EXPECT_LT((k.omega_frame - w_fd).norm(), 1e-6) << "t=" << t;
    EXPECT_LT(
        (k.dR - (kp.T_world_frame.rotationMatrix() - km.T_world_frame.rotationMatrix()) / (2 * h))
            .norm(),
        1e-6);
    EXPECT_LT((k.ddR - (kp.dR - km.dR) / (2 * h)).norm(), 1e-4);  // O(h^2) truncation
    EXPECT_LT((R.transpose() * k.dR + (R.transpose() * k.dR).transpose()).norm(), 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 300);
}

TEST(SimTrajectory, StandsStillThenReturnsExactlyToStart) {
  const Trajectory& traj = defaultWorld().trajectory;
  ASSERT_GE(traj.stillTime(), 2.0);
  const Pose start = traj.T_world_body(0.0);
  const Pose end = traj.T_world_body(traj.duration());
  EXPECT_TRUE(start.isApprox(end, 1e-9, 1e-9));
  for (double t = 0.0; t <= traj.stillTime(); t += 0.1) {
    for (double tt : {t, traj.duration() - t}) {
      const FrameKinematics k = traj.body(tt);
      EXPECT_TRUE(k.T_world_frame.isApprox(start, 1e-9, 1e-9)) << tt;
      EXPECT_LT(k.v_world.norm(), 1e-9) << tt;
      EXPECT_LT(k.a_world.norm(), 1e-9) << tt;
      EXPECT_LT(k.omega_frame.norm(), 1e-9) << tt;
    }
  }
  // ...and actually walks in between.
  EXPECT_GT(traj.body(traj.stillTime() + 3.0).v_world.norm(), 0.2);
}

TEST(SimTrajectory, LidarStartsAtTheWorldOrigin) {
  const BuildingSpec spec = loadBuildingSpec("default");
  const Pose T_world_lidar =
      defaultWorld().trajectory.frame(0.0, spec.sensors.T_body_lidar).T_world_frame;
  EXPECT_LT(T_world_lidar.translation().norm(), 1e-12);
  // Level and facing +x at the start.
  EXPECT_LT(T_world_lidar.angle(), 1e-12);
}

TEST(SimTrajectory, WalkIsPlausibleForALeggedRobot) {
  const BuildingSpec spec = loadBuildingSpec("default");
  const Trajectory& traj = defaultWorld().trajectory;
  double max_speed = 0, max_pitch = 0, max_yaw_rate = 0, max_accel = 0;
  for (double t = 0; t < traj.duration(); t += 0.01) {
    const FrameKinematics k = traj.body(t);
    max_speed = std::max(max_speed, k.v_world.head<2>().norm());
    max_accel = std::max(max_accel, k.a_world.norm());
    const Eigen::Vector3d x_axis = k.T_world_frame.rotationMatrix().col(0);
    max_pitch = std::max(max_pitch, std::asin(std::abs(x_axis.z())));
    max_yaw_rate = std::max(max_yaw_rate, std::abs(k.omega_frame.z()));
  }
  EXPECT_LT(max_speed, spec.robot.walk_speed + 0.1);
  EXPECT_GT(max_speed, spec.robot.walk_speed - 0.1);
  // Pitched with the stairs: riser/tread = 0.17/0.28 -> about 31 deg.
  EXPECT_GT(max_pitch, 25.0 * M_PI / 180);
  EXPECT_LT(max_pitch, 36.0 * M_PI / 180);
  EXPECT_LT(max_yaw_rate, 1.2);
  // Gait bounce dominates: 0.015 m at 2.5 Hz is 3.7 m/s^2.
  EXPECT_GT(max_accel, 2.0);
  EXPECT_LT(max_accel, 8.0);
}

/// The robot never walks through the building: its body centre keeps clear of
/// every surface (the floor is body_height below it).
TEST(SimTrajectory, BodyKeepsClearOfTheBuilding) {
  const World& world = defaultWorld();
  double closest = 1e9, closest_t = 0;
  for (double t = 0; t < world.trajectory.duration(); t += 0.25) {
    const double d = world.building.mesh.distanceTo(world.trajectory.T_world_body(t).translation());
    if (d < closest) {
      closest = d;
      closest_t = t;
    }
  }
  EXPECT_GT(closest, 0.25) << "at t = " << closest_t;  // steps pass 0.28 m below the body centre
}

}  // namespace
}  // namespace storey::sim
