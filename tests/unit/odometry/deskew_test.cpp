// Deskew against the simulator's ground truth: a scan taken while walking,
// deskewed with noise-free IMU data from the true trajectory, must equal the
// scan moved with the true per-point poses.
#include "odometry/deskew.h"

#include <gtest/gtest.h>

#include "imu/imu_pose_table.h"
#include "sim/building_spec.h"
#include "sim/lidar_simulator.h"
#include "sim/trajectory.h"
#include "sim/world.h"

namespace storey {
namespace {

TEST(Deskew, MatchesTheTruePerPointMotion) {
  const sim::BuildingSpec spec = sim::loadBuildingSpec("tiny");
  const sim::World world = sim::makeWorld(spec);
  const sim::LidarSimulator lidar(world.building.mesh, world.trajectory, spec.sensors,
                                  sim::LidarNoise{}, 1);
  const double gravity = spec.sensors.imu.gravity;
  const Pose& T_body_lidar = spec.sensors.T_body_lidar;
  const Pose& T_body_imu = spec.sensors.T_body_imu;

  // A scan while walking (after the 2 s still start).
  const int n = 80;
  const Scan scan = lidar.simulateScan(n);
  const double t_ref = nsToSeconds(scan.stamp_ns);
  ASSERT_GT(t_ref, world.trajectory.stillTime() + 1.0);
  ASSERT_GT(scan.points.size(), 10000u);

  // Noise-free IMU at 400 Hz from the true trajectory, from t_ref - 0.05 s to the scan's end.
  std::vector<ImuSample> imu;
  for (double t = t_ref - 0.05; t < t_ref + 0.15; t += 1.0 / 400.0) {
    const sim::FrameKinematics k = world.trajectory.frame(t, T_body_imu);
    ImuSample s;
    s.stamp_ns = secondsToNs(t);
    s.gyro = k.omega_frame;
    s.accel = sim::specificForce(k, gravity);
    imu.push_back(s);
  }
  const sim::FrameKinematics start = world.trajectory.frame(nsToSeconds(imu[1].stamp_ns), T_body_imu);
  ImuState state;
  state.stamp_ns = imu[1].stamp_ns;
  state.T_world_imu = start.T_world_frame;
  state.v_world_imu = start.v_world;
  const ImuPoseTable table =
      ImuPoseTable::fromSamples(state, imu, scan.stamp_ns + secondsToNs(0.1), gravity);

  SensorConfig sensor;
  sensor.T_imu_lidar = T_body_imu.inverse() * T_body_lidar;
  const Scan deskewed = deskewScan(scan, table, sensor);
  ASSERT_EQ(deskewed.points.size(), scan.points.size());

  const Pose T_ref_world = world.trajectory.frame(t_ref, T_body_lidar).T_world_frame.inverse();
  double max_error = 0.0, max_motion = 0.0;
  for (std::size_t i = 0; i < scan.points.size(); i += 7) {
    const ScanPoint& p = scan.points[i];
    const Pose T_ref_t =
        T_ref_world * world.trajectory.frame(t_ref + p.time, T_body_lidar).T_world_frame;
    const Eigen::Vector3d truth = T_ref_t * p.p.cast<double>();
    max_error = std::max(max_error, (deskewed.points[i].p.cast<double>() - truth).norm());
    max_motion = std::max(max_motion, (p.p.cast<double>() - truth).norm());
  }
  EXPECT_GT(max_motion, 0.02) << "the fixture must move during the scan";
  EXPECT_LT(max_error, 1e-3) << "deskew error (m); the raw scan is off by up to " << max_motion;
}

}  // namespace
}  // namespace storey
