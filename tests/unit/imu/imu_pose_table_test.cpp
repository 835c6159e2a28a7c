#include "imu/imu_pose_table.h"

#include <gtest/gtest.h>

#include <iostream>
#include <random>

#include "common/error.h"
#include "synthetic_imu.h"

namespace storey {
namespace {

using test::angleBetween;
using test::kBaseNs;
using test::SyntheticTrajectory;

std::int64_t ns(double seconds) {
  return kBaseNs + secondsToNs(seconds);
}

// Deskew use: one scan (0.1 s), queried at random times; compared with the
// analytic truth. Error budget: the integration bound of synthetic_imu.h
// (the interpolation inside an interval, Hermite O(dt^4) and rotation
// O(dt^3), is far smaller); at 400 Hz: < 10 um and < 2e-5 rad, far below
// LiDAR noise.
TEST(ImuPoseTable, MatchesTruthInsideTheInterval) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot(
      Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(0, 1, 1).normalized())));
  ImuBias bias;
  bias.gyro = Eigen::Vector3d(0.01, 0.02, -0.01);
  bias.accel = Eigen::Vector3d(0.1, -0.05, 0.2);
  for (double rate : {100.0, 400.0, 1000.0}) {
    test::ImuSimOptions o;
    o.rate_hz = rate;
    o.bias = bias;
    const auto samples = test::simulateImu(tr, o);
    const std::int64_t t0 = ns(0.40321);
    const ImuPoseTable table =
        ImuPoseTable::fromSamples(tr.state(t0, bias), samples, ns(0.50321), 9.81);
    EXPECT_NEAR(table.duration(), 0.1, 1e-12);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(0.0, 0.1);
    double max_rot = 0.0, max_pos = 0.0, max_vel = 0.0, moved = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const double t = uni(rng);
      const ImuState truth = tr.state(t0 + secondsToNs(t), bias);
      const ImuState got = table.stateAt(t);
      max_rot =
          std::max(max_rot, angleBetween(got.T_world_imu.rotation(), truth.T_world_imu.rotation()));
      max_pos = std::max(max_pos,
                         (got.T_world_imu.translation() - truth.T_world_imu.translation()).norm());
      max_vel = std::max(max_vel, (got.v_world_imu - truth.v_world_imu).norm());
      moved = std::max(
          moved, (truth.T_world_imu.translation() - table.T_world_imu(0.0).translation()).norm());
    }
    std::cout << "[ measured ] pose table at " << rate << " Hz over 0.1 s: rotation " << max_rot
              << " rad, position " << max_pos << " m, velocity " << max_vel << " m/s\n";
    EXPECT_GT(moved, 0.05);  // fixture check: the IMU moves during the scan
    const test::IntegrationErrorBound b = test::integrationErrorBound(tr, rate, 0.40321, 0.50321);
    EXPECT_LT(max_rot, b.rotation) << rate;
    EXPECT_LT(max_pos, b.position) << rate;
    EXPECT_LT(max_vel, b.velocity) << rate;
  }
}

TEST(ImuPoseTable, ExactAtKnotsAndContinuousAtTheEnds) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  test::ImuSimOptions o;
  const auto samples = test::simulateImu(tr, o);
  const std::int64_t t0 = ns(0.1);  // on a sample: knots at multiples of 2.5 ms
  const ImuPoseTable table = ImuPoseTable::fromSamples(tr.state(t0), samples, ns(0.2), 9.81);
  EXPECT_EQ(table.startNs(), t0);
  EXPECT_EQ(table.endNs(), ns(0.2));
  EXPECT_EQ(table.endState().stamp_ns, ns(0.2));
  EXPECT_TRUE(table.T_world_imu(0.0).isApprox(tr.state(t0).T_world_imu, 1e-15, 1e-15));
  const Pose end = table.endState().T_world_imu;
  const double T = table.duration();
  EXPECT_TRUE(table.T_world_imu(T).isApprox(end, 1e-12, 1e-12));
  EXPECT_TRUE(table.T_world_imu(T - 1e-9).isApprox(end, 1e-8, 1e-8));
  EXPECT_TRUE(table.T_world_imu(T + 1e-9).isApprox(end, 1e-8, 1e-8));
  EXPECT_TRUE(table.T_world_imu(-1e-9).isApprox(table.T_world_imu(1e-9), 1e-8, 1e-8));
  // Extrapolation beyond the end: constant velocity, small error over 1 ms.
  const Pose truth = tr.state(ns(0.201)).T_world_imu;
  EXPECT_TRUE(table.T_world_imu(T + 1e-3).isApprox(truth, 1e-5, 1e-5));
  // Query stamp helper.
  EXPECT_NEAR(table.secondsSinceStart(ns(0.15), -0.01), 0.04, 1e-12);
  // A start state at another time is refused.
  EXPECT_THROW(ImuPoseTable(tr.state(t0 + 1), sliceImuSignal(samples, t0, ns(0.2)), 9.81), Error);
}

TEST(ImuPoseTable, IrregularSamplesAndDropouts) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  test::ImuSimOptions o;
  o.rate_hz = 1000;
  auto samples = test::simulateImu(tr, o);
  // Drop 3 of every 4 samples between 0.15 and 0.17 s, and jitter the rest.
  std::vector<ImuSample> irregular;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double t = test::secondsSinceBase(samples[k].stamp_ns);
    if (t > 0.15 && t < 0.17 && k % 4 != 0) continue;
    irregular.push_back(samples[k]);
  }
  const std::int64_t t0 = ns(0.1);
  const ImuPoseTable table = ImuPoseTable::fromSamples(tr.state(t0), irregular, ns(0.2), 9.81);
  double max_pos = 0.0;
  for (double t = 0.0; t <= 0.1; t += 1e-4) {
    max_pos = std::max(max_pos, (table.T_world_imu(t).translation() -
                                 tr.state(t0 + secondsToNs(t)).T_world_imu.translation())
                                    .norm());
  }
  EXPECT_LT(max_pos, 5e-6);
}

}  // namespace
}  // namespace storey
