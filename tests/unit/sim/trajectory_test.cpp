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

/// Velocity, acceleration, angular rate, dR and ddR of a mounted frame
/// against central differences of the pose, every 0.37 s of the walk.
void expectDerivativesMatchFiniteDifferences(const Trajectory& traj) {
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

TEST(SimTrajectory, DerivativesMatchFiniteDifferences) {
  expectDerivativesMatchFiniteDifferences(defaultWorld().trajectory);
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

/// robot.rounds: the route walked again and again without stopping between
/// rounds (a long log from one building), still only at both ends.
TEST(SimTrajectory, RoundsWalkTheRouteAgainWithoutStopping) {
  BuildingSpec spec = loadBuildingSpec("default");
  spec.robot.rounds = 3;
  // The key reads back from the spec file a simulation writes.
  EXPECT_EQ(parseBuildingSpec(buildingSpecYaml(spec), "spec.yaml").robot.rounds, 3);
  const World world = makeWorld(spec);
  const Trajectory& once = defaultWorld().trajectory;
  const Trajectory& traj = world.trajectory;
  EXPECT_NEAR(traj.pathLength(), 3.0 * once.pathLength(), 0.001 * once.pathLength());
  const double walk_once = once.duration() - 2.0 * once.stillTime();
  const double walk = traj.duration() - 2.0 * traj.stillTime();
  // No stop and restart between rounds: shorter than three walks, not by much.
  EXPECT_LT(walk, 3.0 * walk_once);
  EXPECT_GT(walk, 3.0 * walk_once - 10.0);
  EXPECT_TRUE(traj.T_world_body(0.0).isApprox(traj.T_world_body(traj.duration()), 1e-9, 1e-9));
  // Passing the start between the rounds, at walking speed.
  const Eigen::Vector3d start = traj.T_world_body(0.0).translation();
  for (int round = 1; round < 3; ++round) {
    const double around = traj.stillTime() + round * walk / 3.0;
    double closest = 1e9, speed = 0.0;
    for (double t = around - 20.0; t < around + 20.0; t += 0.01) {
      const FrameKinematics k = traj.body(t);
      const double d = (k.T_world_frame.translation() - start).norm();
      if (d < closest) {
        closest = d;
        speed = k.v_world.norm();
      }
    }
    EXPECT_LT(closest, 0.05) << "round " << round;
    EXPECT_GT(speed, 0.5) << "round " << round;
  }
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

/// The body centre's closest approach to any surface over the walk [m] and when [s].
std::pair<double, double> closestApproach(const World& world) {
  double closest = 1e9, closest_t = 0;
  for (double t = 0; t < world.trajectory.duration(); t += 0.25) {
    const double d = world.building.mesh.distanceTo(world.trajectory.T_world_body(t).translation());
    if (d < closest) {
      closest = d;
      closest_t = t;
    }
  }
  return {closest, closest_t};
}

/// The robot never walks through the building: its body centre keeps clear of
/// every surface (the floor is body_height below it).
TEST(SimTrajectory, BodyKeepsClearOfTheBuilding) {
  const auto [closest, closest_t] = closestApproach(defaultWorld());
  EXPECT_GT(closest, 0.25) << "at t = " << closest_t;  // steps pass 0.28 m below the body centre
}

const World& handheldWorld() {
  static const World world = [] {
    BuildingSpec spec = loadBuildingSpec("default");
    spec.robot = robotForMotion(RobotMotion::kHandheld);
    return makeWorld(spec);
  }();
  return world;
}

/// Roll and pitch of R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Vector2d rollPitch(const Eigen::Matrix3d& R) {
  return Eigen::Vector2d(std::atan2(R(2, 1), R(2, 2)), -std::asin(R(2, 0)));
}

TEST(SimTrajectory, HandheldDerivativesMatchFiniteDifferences) {
  expectDerivativesMatchFiniteDifferences(handheldWorld().trajectory);
}

TEST(SimTrajectory, HandheldStandsStillThenReturnsExactlyToStart) {
  const Trajectory& traj = handheldWorld().trajectory;
  const Pose start = traj.T_world_body(0.0);
  EXPECT_TRUE(start.isApprox(traj.T_world_body(traj.duration()), 1e-9, 1e-9));
  for (double t : {0.0, 1.0, traj.stillTime(), traj.duration() - 1.0}) {
    const FrameKinematics k = traj.body(t);
    EXPECT_TRUE(k.T_world_frame.isApprox(start, 1e-9, 1e-9)) << t;
    EXPECT_LT(k.v_world.norm() + k.a_world.norm() + k.omega_frame.norm(), 1e-9) << t;
  }
}

/// A person's walk: about 1 m/s on floors and 0.5 m/s on the stairs, a
/// 4 cm bounce at 1.9 steps per second, a few degrees of sway, turns of up
/// to 90 deg/s, the device pitched with half the stair slope.
TEST(SimTrajectory, HandheldWalkIsPlausibleForAPerson) {
  const World& world = handheldWorld();
  const Trajectory& traj = world.trajectory;
  const RobotSpec robot = robotForMotion(RobotMotion::kHandheld);
  const HandheldGaitSpec& gait = robot.handheld_gait;
  double max_floor_speed = 0, max_stair_speed = 0, max_yaw_rate = 0, max_roll = 0;
  double max_stair_pitch = 0, max_floor_yaw_rate = 0, max_slope = 0;
  for (double t = 0.5; t < traj.duration() - 0.5; t += 0.01) {
    const FrameKinematics k = traj.body(t);
    const Eigen::Vector2d rp = rollPitch(k.T_world_frame.rotationMatrix());
    max_roll = std::max(max_roll, std::abs(rp.x()));
    max_yaw_rate = std::max(max_yaw_rate, std::abs(k.omega_frame.z()));
    // In half a second the bounce moves the device 7 mm up or down at most,
    // the stairs 0.13 m.
    const Eigen::Vector3d p0 = traj.T_world_body(t - 0.5).translation();
    const Eigen::Vector3d p1 = k.T_world_frame.translation();
    const Eigen::Vector3d p2 = traj.T_world_body(t + 0.5).translation();
    const double rise0 = p1.z() - p0.z(), rise1 = p2.z() - p1.z();
    bool level = true;  // no flight within 2 s
    for (double dt = -2.0; dt <= 2.0 && level; dt += 0.25)
      level = std::abs(traj.T_world_body(t + dt).translation().z() - p1.z()) < 0.02;
    if (std::abs(rise0) > 0.1 && std::abs(rise1) > 0.1) {  // on a flight for the whole second
      max_stair_speed = std::max(max_stair_speed, (p2 - p0).norm());
      max_stair_pitch = std::max(max_stair_pitch, std::abs(rp.y()));
      max_slope =
          std::max(max_slope, std::atan2(std::abs(p2.z() - p0.z()), (p2 - p0).head<2>().norm()));
    } else if (level) {
      max_floor_speed = std::max(max_floor_speed, k.v_world.head<2>().norm());
      max_floor_yaw_rate = std::max(max_floor_yaw_rate, std::abs(k.omega_frame.z()));
    }
  }
  EXPECT_GT(max_floor_speed, 0.95);
  EXPECT_LT(max_floor_speed, 1.1);  // the sway adds a little
  EXPECT_GT(max_stair_speed, 0.45);
  EXPECT_LT(max_stair_speed, 0.55);
  // Turns at up to 90 deg/s, plus the yaw sway's rate. The planner's heading
  // samples (one per 1 cm chord of the corner's arc) ripple the rate by up to
  // 10 % (the robot's too); where a corner joins a flight to a landing the
  // heading turns up to 1 / cos(slope) faster than the 3D direction the
  // planner limits.
  const double sway_rate = gait.yaw * M_PI * gait.frequency;
  EXPECT_GT(max_floor_yaw_rate, 80 * M_PI / 180);
  EXPECT_LT(max_floor_yaw_rate, 1.1 * robot.max_yaw_rate + sway_rate + 0.02);
  EXPECT_LT(max_yaw_rate, 1.1 * robot.max_yaw_rate / std::cos(34 * M_PI / 180) + sway_rate);
  EXPECT_NEAR(max_roll, gait.roll, 0.2 * gait.roll);
  // Half the flights' slope (about 34 deg), plus the step pitch.
  EXPECT_GT(max_slope, 30 * M_PI / 180);
  EXPECT_NEAR(max_stair_pitch, gait.slope_pitch * max_slope + gait.pitch, 1.2 * M_PI / 180);

  // On the ground-floor corridor at full speed: 2 * bounce of height change,
  // 1.9 bounces per second.
  double t0 = traj.stillTime() + 4.0;
  double z_min = 1e9, z_max = -1e9;
  int peaks = 0;
  double previous_vz = traj.body(t0).v_world.z();
  for (double t = t0; t < t0 + 5.0; t += 0.002) {
    const FrameKinematics k = traj.body(t);
    ASSERT_GT(k.v_world.head<2>().norm(), 0.9) << "not at full speed at t = " << t;
    z_min = std::min(z_min, k.T_world_frame.translation().z());
    z_max = std::max(z_max, k.T_world_frame.translation().z());
    if (previous_vz > 0 && k.v_world.z() <= 0) ++peaks;
    previous_vz = k.v_world.z();
  }
  EXPECT_NEAR(z_max - z_min, 2 * gait.bounce, 0.003);
  EXPECT_GE(z_max - z_min, 0.03);
  EXPECT_LE(z_max - z_min, 0.05);
  EXPECT_NEAR(peaks, 5.0 * gait.frequency, 1.0);
}

TEST(SimTrajectory, HandheldBodyKeepsClearOfTheBuilding) {
  const auto [closest, closest_t] = closestApproach(handheldWorld());
  EXPECT_GT(closest, 0.3) << "at t = " << closest_t;
}

}  // namespace
}  // namespace storey::sim
