// TimeOffsetEstimator on synthetic rotations: a gyro signal of a turning
// sensor, its rotations over scan intervals integrated once at the true
// times and once shifted by the offset.
#include "odometry/time_offset_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "imu/so3.h"

namespace storey {
namespace {

/// Body rate of a sensor turning back and forth about a tilted axis [rad/s].
Eigen::Vector3d rate(double t, double amplitude) {
  return amplitude * Eigen::Vector3d(0.3 * std::sin(1.1 * t), 0.2 * std::cos(0.7 * t),
                                     std::sin(2.0 * t) + 0.5 * std::sin(5.3 * t));
}

/// Rotation over [t0, t1] by fine midpoint integration of rate().
Eigen::Quaterniond integrate(double t0, double t1, double amplitude) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  const int steps = 200;
  const double h = (t1 - t0) / steps;
  for (int i = 0; i < steps; ++i)
    q = q * so3::expQuaternion(rate(t0 + (i + 0.5) * h, amplitude) * h);
  return q.normalized();
}

/// Feeds `pairs` scan intervals of 0.1 s: the LiDAR sees the true rotation
/// (plus noise), the gyro's is that of the interval shifted by -offset.
TimeOffsetEstimate run(double offset, double amplitude, int pairs, double noise,
                       Eigen::Vector3d gyro_bias_error = Eigen::Vector3d::Zero(),
                       int outliers = 0) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, noise);
  TimeOffsetEstimator estimator;
  for (int k = 0; k < pairs; ++k) {
    const double t = 0.1 * k;
    Eigen::Quaterniond lidar = integrate(t, t + 0.1, amplitude) *
                               so3::expQuaternion(Eigen::Vector3d(n(rng), n(rng), n(rng)));
    if (k < outliers) lidar = lidar * so3::expQuaternion(Eigen::Vector3d(0.02, -0.01, 0.015));
    const Eigen::Quaterniond gyro = integrate(t - offset, t + 0.1 - offset, amplitude) *
                                    so3::expQuaternion(gyro_bias_error * 0.1);
    estimator.add(lidar, gyro, rate(t - offset, amplitude), rate(t + 0.1 - offset, amplitude));
  }
  return estimator.estimate();
}

TEST(TimeOffsetEstimator, FindsTheOffsetAndItsSign) {
  for (const double offset : {0.010, -0.010, 0.003, 0.020}) {
    const TimeOffsetEstimate e = run(offset, 1.0, 600, 2e-4);
    ASSERT_TRUE(e.valid());
    EXPECT_NEAR(e.offset_s, offset, 0.1 * std::abs(offset) + 3.0 * e.sigma_s) << offset;
    EXPECT_LT(e.sigma_s, 0.001);
    EXPECT_TRUE(e.detected()) << offset;
  }
}

TEST(TimeOffsetEstimator, NoOffsetIsNotDetected) {
  const TimeOffsetEstimate e = run(0.0, 1.0, 600, 2e-4);
  ASSERT_TRUE(e.valid());
  EXPECT_NEAR(e.offset_s, 0.0, 3.0 * e.sigma_s + 2e-4);
  EXPECT_FALSE(e.detected());
}

TEST(TimeOffsetEstimator, AGyroBiasErrorIsNotAnOffset) {
  // A constant error of the gyro bias leaves a constant rotation residual.
  const TimeOffsetEstimate e = run(0.0, 1.0, 600, 2e-4, Eigen::Vector3d(0.01, -0.005, 0.008));
  ASSERT_TRUE(e.valid());
  EXPECT_FALSE(e.detected()) << e.offset_s;
}

TEST(TimeOffsetEstimator, RegistrationFailuresDoNotMoveIt) {
  const TimeOffsetEstimate e = run(0.010, 1.0, 600, 2e-4, Eigen::Vector3d::Zero(), 30);
  ASSERT_TRUE(e.valid());
  EXPECT_NEAR(e.offset_s, 0.010, 0.0015);
}

TEST(TimeOffsetEstimator, WithoutTurnsOrScansThereIsNoEstimate) {
  EXPECT_FALSE(run(0.010, 0.0, 600, 2e-4).valid());  // no rotation: no signal
  EXPECT_FALSE(run(0.010, 1.0, 20, 2e-4).valid());   // too few pairs
  EXPECT_FALSE(TimeOffsetEstimator().estimate().detected());
}

}  // namespace
}  // namespace storey
