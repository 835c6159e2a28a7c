// Filling an IMU dropout (odometry/imu_gap_fill.h): the filled samples hold
// the motion at constant velocity and turn rate, marked as not measured.
#include "odometry/imu_gap_fill.h"

#include <gtest/gtest.h>

#include "imu/imu_preintegration.h"
#include "imu/so3.h"

namespace storey {
namespace {

std::int64_t ns(double seconds) {
  return secondsToNs(seconds);
}

ImuNoise noiseAt(double rate_hz) {
  ImuNoise noise;
  noise.rate_hz = rate_hz;
  noise.gravity = 9.81;
  return noise;
}

ImuSample sampleAt(double t) {
  ImuSample s;
  s.stamp_ns = ns(t);
  return s;
}

TEST(ImuGapFill, ADropoutIsAWideSpacingOrARemovedRun) {
  const ImuNoise at400 = noiseAt(400.0), at100 = noiseAt(100.0);
  // 400 Hz: the threshold is 50 ms (5 periods would be 12.5 ms); 100 Hz: 50 ms.
  EXPECT_FALSE(isImuDropout(sampleAt(1.0), sampleAt(1.049), at400));
  EXPECT_TRUE(isImuDropout(sampleAt(1.0), sampleAt(1.051), at400));
  EXPECT_FALSE(isImuDropout(sampleAt(1.0), sampleAt(1.049), at100));
  ImuSample after_removed = sampleAt(1.0025);  // one period later, after a removed run
  after_removed.after_removed = true;
  EXPECT_TRUE(isImuDropout(sampleAt(1.0), after_removed, at400));
}

TEST(ImuGapFill, TheMeanIsOfTheMeasuredSamplesOfTheLastSpan) {
  std::vector<ImuSample> samples;
  for (int k = 0; k < 400; ++k) {
    ImuSample s = sampleAt(0.01 * k);
    s.gyro = Eigen::Vector3d(k < 200 ? 5.0 : 1.0, 0.0, 0.0);
    s.accel = Eigen::Vector3d(0.0, 0.0, k < 200 ? -3.0 : 9.0);
    s.filled = k >= 300;  // not measured: left out
    if (s.filled) s.gyro.x() = 100.0;
    samples.push_back(s);
  }
  // The second before 2.99 s: samples 199..299 (t >= 1.99 s), one of them before the change.
  const ImuMean mean = meanOfMeasured(samples, ns(2.99), ns(1.0));
  EXPECT_NEAR(mean.gyro.x(), (5.0 + 100 * 1.0) / 101, 1e-12);
  EXPECT_NEAR(mean.accel.z(), (-3.0 + 100 * 9.0) / 101, 1e-12);
  // Before 3.5 s: the filled ones are skipped, the measured ones of [2.5, 2.99] count.
  EXPECT_NEAR(meanOfMeasured(samples, ns(3.5), ns(1.0)).gyro.x(), 1.0, 1e-12);
  // At least the last measured sample, whatever the span.
  EXPECT_NEAR(meanOfMeasured(samples, ns(3.995), 0).gyro.x(), 1.0, 1e-12);
  EXPECT_NEAR(meanOfMeasured(samples, ns(1.995), 0).gyro.x(), 5.0, 1e-12);
}

// Integrated like any IMU signal, the fill keeps the velocity and turns at
// the held rate: it is the constant-velocity model.
TEST(ImuGapFill, TheFillIsConstantVelocityAtTheHeldTurnRate) {
  const ImuNoise noise = noiseAt(400.0);
  ImuGapMotion motion;
  motion.state_known = true;
  motion.q_world_imu = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                                          Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
  motion.g_world = Eigen::Vector3d(0.0, 0.0, -9.81);
  motion.bias.gyro = Eigen::Vector3d(0.01, -0.02, 0.005);
  motion.bias.accel = Eigen::Vector3d(0.05, 0.1, -0.08);
  motion.gyro = motion.bias.gyro + Eigen::Vector3d(0.05, -0.03, 0.3);  // turning left
  const std::vector<ImuSample> fill = fillImuGap(ns(10.0), ns(12.0), motion, noise);
  // Every 2.5 ms from 10.0025 s to 11.9975 s.
  ASSERT_EQ(fill.size(), 799u);
  EXPECT_EQ(fill.front().stamp_ns, ns(10.0025));
  EXPECT_EQ(fill.back().stamp_ns, ns(11.9975));
  for (const ImuSample& s : fill) {
    EXPECT_TRUE(s.filled);
    EXPECT_FALSE(s.after_removed);
  }

  // Preintegrate [first fill, last fill] and predict from a moving state.
  ImuState start;
  start.stamp_ns = fill.front().stamp_ns;
  const double tau0 = 0.0025;
  const Eigen::Vector3d rate = motion.gyro - motion.bias.gyro;
  start.T_world_imu =
      Pose(motion.q_world_imu * so3::expQuaternion(rate * tau0), Eigen::Vector3d(1, 2, 3));
  start.v_world_imu = Eigen::Vector3d(1.2, 0.3, -0.1);
  start.bias = motion.bias;
  const ImuPreintegration pre = ImuPreintegration::fromSamples(
      fill, fill.front().stamp_ns, fill.back().stamp_ns, motion.bias, noise);
  const ImuState end = pre.predict(start);
  const double Dt = pre.duration();
  EXPECT_LT((end.v_world_imu - start.v_world_imu).norm(), 1e-9);
  EXPECT_LT(
      (end.T_world_imu.translation() - (start.T_world_imu.translation() + start.v_world_imu * Dt))
          .norm(),
      1e-9);
  const Eigen::Quaterniond expected = start.T_world_imu.rotation() * so3::expQuaternion(rate * Dt);
  EXPECT_LT(expected.angularDistance(end.T_world_imu.rotation()), 1e-9);
}

TEST(ImuGapFill, WithoutAStateTheForceIsHeld) {
  ImuGapMotion motion;
  motion.gyro = Eigen::Vector3d(0.0, 0.0, 0.1);
  motion.accel = Eigen::Vector3d(0.2, -0.1, 9.7);
  const std::vector<ImuSample> fill = fillImuGap(ns(3.0), ns(3.1), motion, noiseAt(100.0));
  ASSERT_EQ(fill.size(), 9u);  // 3.01 .. 3.09
  for (const ImuSample& s : fill) {
    EXPECT_EQ(s.accel, motion.accel);
    EXPECT_EQ(s.gyro, motion.gyro);
  }
  // Longer than any motion model holds: left to the interpolation.
  EXPECT_EQ(fillImuGap(ns(3.0), ns(3.0) + kMaxFilledImuGapNs, motion, noiseAt(100.0)).size(), 999u);
  EXPECT_TRUE(
      fillImuGap(ns(3.0), ns(3.0) + kMaxFilledImuGapNs + 1, motion, noiseAt(100.0)).empty());
}

}  // namespace
}  // namespace storey
