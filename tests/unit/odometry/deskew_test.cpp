// Deskew against the simulator's ground truth: a scan taken while walking,
// deskewed with noise-free IMU data from the true trajectory, must equal the
// scan moved with the true per-point poses.
#include "odometry/deskew.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "imu/imu_pose_table.h"
#include "sim/building_spec.h"
#include "sim/lidar_simulator.h"
#include "sim/trajectory.h"
#include "sim/world.h"

namespace storey {
namespace {

/// A scan of `tiny` taken while walking and the IMU pose table over it, made
/// with noise-free IMU data from the true trajectory.
struct WalkingScan {
  sim::BuildingSpec spec = sim::loadBuildingSpec("tiny");
  sim::World world = sim::makeWorld(spec);
  Scan scan =
      sim::LidarSimulator(world.building.mesh, world.trajectory, spec.sensors, sim::LidarNoise{}, 1)
          .simulateScan(80);  // after the 2 s still start
  ImuPoseTable table = tableOver(scan);
  SensorConfig sensor = sensorOf(spec);

  static SensorConfig sensorOf(const sim::BuildingSpec& spec) {
    SensorConfig sensor;
    sensor.T_imu_lidar = spec.sensors.T_body_imu.inverse() * spec.sensors.T_body_lidar;
    return sensor;
  }

  ImuPoseTable tableOver(const Scan& scan) const {
    const double gravity = spec.sensors.imu.gravity;
    const Pose& T_body_imu = spec.sensors.T_body_imu;
    const double t_ref = nsToSeconds(scan.stamp_ns);
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
    const sim::FrameKinematics start =
        world.trajectory.frame(nsToSeconds(imu[1].stamp_ns), T_body_imu);
    ImuState state;
    state.stamp_ns = imu[1].stamp_ns;
    state.T_world_imu = start.T_world_frame;
    state.v_world_imu = start.v_world;
    return ImuPoseTable::fromSamples(state, imu, scan.stamp_ns + secondsToNs(0.1), gravity);
  }
};

TEST(Deskew, MatchesTheTruePerPointMotion) {
  const WalkingScan fixture;
  const sim::World& world = fixture.world;
  const Scan& scan = fixture.scan;
  const Pose& T_body_lidar = fixture.spec.sensors.T_body_lidar;
  const double t_ref = nsToSeconds(scan.stamp_ns);
  ASSERT_GT(t_ref, world.trajectory.stillTime() + 1.0);
  ASSERT_GT(scan.points.size(), 10000u);

  const Scan deskewed = deskewScan(scan, fixture.table, fixture.sensor);
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

TEST(Deskew, ABeamOrderedScanGetsEachPointsOwnTransform) {
  // An Ouster's cloud is row after row: every column's time comes back once per
  // beam, far from the point before. Each point must be moved exactly as it
  // would be alone (the transform of its own time), whether computed or kept.
  const WalkingScan fixture;
  Scan scan = fixture.scan;
  const double columns = 1024.0;
  const auto [t_first, t_last] = scan.timeSpan();
  for (ScanPoint& p : scan.points)
    p.time = static_cast<float>(
        t_first + std::floor((p.time - t_first) / (t_last - t_first) * (columns - 1.0)) / columns *
                      (t_last - t_first));
  std::stable_sort(scan.points.begin(), scan.points.end(),
                   [](const ScanPoint& a, const ScanPoint& b) { return a.ring < b.ring; });
  const Scan deskewed = deskewScan(scan, fixture.table, fixture.sensor);
  ASSERT_EQ(deskewed.points.size(), scan.points.size());
  std::size_t repeated_times = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    Scan alone;
    alone.stamp_ns = scan.stamp_ns;
    alone.points = {scan.points[i]};
    const Eigen::Vector3f expected = deskewScan(alone, fixture.table, fixture.sensor).points[0].p;
    ASSERT_EQ(std::memcmp(expected.data(), deskewed.points[i].p.data(), sizeof(expected)), 0)
        << "point " << i << " at " << scan.points[i].time << " s";
    if (i > 0 && scan.points[i].ring != scan.points[i - 1].ring) ++repeated_times;
  }
  EXPECT_GE(repeated_times, 10u) << "the fixture must come back to earlier times";
}

}  // namespace
}  // namespace storey
