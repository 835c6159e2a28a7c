#include "imu/imu_signal.h"

#include <gtest/gtest.h>

#include "common/error.h"

namespace storey {
namespace {

/// Samples every 2.5 ms from t0 with gyro = (t, 2t, 3t) (t in ms) and accel = -gyro.
std::vector<ImuSample> linearSamples(std::int64_t t0, int count) {
  std::vector<ImuSample> s(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    s[k].stamp_ns = t0 + k * 2'500'000;
    const double ms = (s[k].stamp_ns - t0) * 1e-6;
    s[k].gyro = Eigen::Vector3d(ms, 2 * ms, 3 * ms);
    s[k].accel = -s[k].gyro;
  }
  return s;
}

TEST(ImuSignal, InterpolatesAtBothEndsAndKeepsInnerSamples) {
  const std::int64_t t0 = 1'700'000'000'000'000'000;
  const auto samples = linearSamples(t0, 20);
  const std::int64_t start = t0 + 3'100'000;  // between samples 1 and 2
  const std::int64_t end = t0 + 20'300'000;   // between samples 8 and 9
  const ImuSignal s = sliceImuSignal(samples, start, end);
  ASSERT_EQ(s.knots.size(), 2u + 7u);  // samples 2..8 inside
  EXPECT_EQ(s.start_ns, start);
  EXPECT_EQ(s.end_ns, end);
  EXPECT_DOUBLE_EQ(s.knots.front().t, 0.0);
  EXPECT_NEAR(s.knots.back().t, 17.2e-3, 1e-15);
  EXPECT_NEAR(s.knots.front().gyro.y(), 2 * 3.1, 1e-12);
  EXPECT_NEAR(s.knots.back().accel.z(), -3 * 20.3, 1e-12);
  EXPECT_NEAR(s.knots[1].t, 5.0e-3 - 3.1e-3, 1e-15);
  EXPECT_NEAR(s.max_gap, 2.5e-3, 1e-15);
  EXPECT_NEAR(s.duration(), 17.2e-3, 1e-15);
}

TEST(ImuSignal, BoundariesOnSamplesAndDuplicateStampsAreNotRepeated) {
  const std::int64_t t0 = 0;
  auto samples = linearSamples(t0, 10);
  samples.insert(samples.begin() + 4, samples[4]);  // duplicate stamp
  const ImuSignal s = sliceImuSignal(samples, samples[1].stamp_ns, samples[7].stamp_ns);
  ASSERT_EQ(s.knots.size(), 6u);  // samples 1..6 of the original (7 with the duplicate)
  for (std::size_t k = 1; k < s.knots.size(); ++k)
    EXPECT_NEAR(s.knots[k].t - s.knots[k - 1].t, 2.5e-3, 1e-15);
}

TEST(ImuSignal, ErrorsNameTheProblem) {
  const auto samples = linearSamples(0, 10);
  try {
    sliceImuSignal(samples, 1'000'000, 30'000'000);
    FAIL() << "expected storey::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("IMU samples cover"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sliceImuSignal(samples, 5'000'000, 5'000'000), Error);
  EXPECT_THROW(sliceImuSignal(samples, 6'000'000, 5'000'000), Error);
  EXPECT_THROW(sliceImuSignal(std::vector<ImuSample>(), 0, 1), Error);
  auto backwards = samples;
  std::swap(backwards[4].stamp_ns, backwards[5].stamp_ns);
  EXPECT_THROW(sliceImuSignal(backwards, 1'000'000, 20'000'000), Error);
  auto nan = samples;
  nan[3].gyro.x() = std::nan("");
  EXPECT_THROW(sliceImuSignal(nan, 1'000'000, 20'000'000), Error);
}

}  // namespace
}  // namespace storey
