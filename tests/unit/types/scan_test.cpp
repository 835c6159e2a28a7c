#include "types/scan.h"

#include <gtest/gtest.h>

#include "types/imu_sample.h"

namespace storey {
namespace {

TEST(Scan, TimeSpanAndStamp) {
  Scan scan;
  scan.stamp_ns = 1'700'000'000'123'456'789;
  EXPECT_EQ(scan.timeSpan(), (std::pair<float, float>(0.0f, 0.0f)));
  for (float t : {0.02f, -0.05f, 0.07f}) {
    ScanPoint p;
    p.time = t;
    scan.points.push_back(p);
  }
  EXPECT_EQ(scan.timeSpan().first, -0.05f);
  EXPECT_EQ(scan.timeSpan().second, 0.07f);
  EXPECT_NEAR(scan.time(), 1700000000.123456789, 1e-6);
}

TEST(ImuSample, FiniteCheck) {
  ImuSample s;
  EXPECT_TRUE(s.isFinite());
  s.accel.z() = NAN;
  EXPECT_FALSE(s.isFinite());
}

TEST(Time, NanosecondRoundTrip) {
  const std::int64_t ns = 1'700'000'000'123'456'789;
  EXPECT_LE(std::llabs(secondsToNs(nsToSeconds(ns)) - ns), 256);
}

}  // namespace
}  // namespace storey
