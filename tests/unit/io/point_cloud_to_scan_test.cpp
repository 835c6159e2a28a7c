// Per-topic conversion of clouds into Scans: ring numbering (from the field,
// renumbered top-down rings, derived from elevation), times from azimuth,
// spin period estimate, dropped-point counts, one warning per topic.
#include "io/point_cloud_to_scan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/log.h"
#include "io/azimuth_time.h"
#include "io/lidar_rings.h"
#include "unit/io/cloud_fixtures.h"

namespace storey {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr std::int64_t kStamp = 1'700'000'000'000'000'000;

/// Captures warnings for the lifetime of the object.
class CapturedLog {
 public:
  CapturedLog() {
    setLogSink([this](LogLevel level, const std::string& m) {
      if (level == LogLevel::kWarning) warnings.push_back(m);
    });
  }
  ~CapturedLog() { setLogSink(nullptr); }
  std::vector<std::string> warnings;
};

/// A point at `range` metres, azimuth `azimuth` and elevation `elevation` [rad].
std::vector<float> polar(double range, double azimuth, double elevation) {
  return {static_cast<float>(range * std::cos(elevation) * std::cos(azimuth)),
          static_cast<float>(range * std::cos(elevation) * std::sin(azimuth)),
          static_cast<float>(range * std::sin(elevation))};
}

TEST(IoLidarRings, ModelTables) {
  const auto vlp = laserElevations(LidarModel::kVlp16);
  ASSERT_EQ(vlp.size(), 16u);
  EXPECT_NEAR(vlp.front(), -15 * kDeg, 1e-12);
  EXPECT_NEAR(vlp[1], -13 * kDeg, 1e-12);
  EXPECT_NEAR(vlp.back(), 15 * kDeg, 1e-12);
  const auto hdl = laserElevations(LidarModel::kHdl32e);
  ASSERT_EQ(hdl.size(), 32u);
  EXPECT_NEAR(hdl.front(), -30.67 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(hdl.back(), 10.67 * kDeg, 0.01 * kDeg);
  const auto vlp32c = laserElevations(LidarModel::kVlp32c);  // uneven, ascending
  ASSERT_EQ(vlp32c.size(), 32u);
  EXPECT_TRUE(std::is_sorted(vlp32c.begin(), vlp32c.end()));
  EXPECT_NEAR(vlp32c.front(), -25 * kDeg, 1e-12);
  EXPECT_NEAR(vlp32c[1], -15.639 * kDeg, 1e-12);
  EXPECT_NEAR(vlp32c[20], 0.0, 1e-12);  // 20 lasers below the horizon
  EXPECT_NEAR(vlp32c.back(), 15 * kDeg, 1e-12);
  const auto os1 = laserElevations(LidarModel::kOs1_64);
  ASSERT_EQ(os1.size(), 64u);
  EXPECT_NEAR(os1.front(), -16.6 * kDeg, 1e-12);
  EXPECT_NEAR(os1.back(), 16.6 * kDeg, 1e-12);
  EXPECT_TRUE(laserElevations(LidarModel::kGeneric).empty());
}

TEST(IoLidarRings, NearestRingAndClusters) {
  const auto vlp = laserElevations(LidarModel::kVlp16);
  EXPECT_EQ(nearestRing(vlp, -20 * kDeg), 0);
  EXPECT_EQ(nearestRing(vlp, -12.9 * kDeg), 1);
  EXPECT_EQ(nearestRing(vlp, 0.9 * kDeg), 8);
  EXPECT_EQ(nearestRing(vlp, 40 * kDeg), 15);

  std::vector<double> elevations;
  for (int ring = 0; ring < 5; ++ring) {
    for (int k = 0; k < 100; ++k)
      elevations.push_back((-3.0 + 1.5 * ring + 0.001 * (k % 7)) * kDeg);
  }
  elevations.push_back(0.7 * kDeg);  // one stray return between beams
  const auto clusters = clusterElevations(elevations, 0.15 * kDeg);
  ASSERT_EQ(clusters.size(), 5u);
  for (int ring = 0; ring < 5; ++ring)
    EXPECT_NEAR(clusters[ring], (-3.0 + 1.5 * ring + 0.003) * kDeg, 1e-3 * kDeg);
}

TEST(IoAzimuthTime, ClockwiseSpinFromFirstPoint) {
  std::vector<ScanPoint> points(4);
  const double azimuths[] = {0.0, -M_PI / 2, -M_PI, M_PI / 2};  // clockwise quarter turns
  for (int i = 0; i < 4; ++i) {
    points[i].p = Eigen::Vector3f(std::cos(azimuths[i]), std::sin(azimuths[i]), 0.0f);
  }
  assignTimesFromAzimuth(points, 0.1);
  EXPECT_FLOAT_EQ(points[0].time, 0.0f);
  EXPECT_FLOAT_EQ(points[1].time, 0.025f);
  EXPECT_FLOAT_EQ(points[2].time, 0.05f);
  EXPECT_FLOAT_EQ(points[3].time, 0.075f);
}

TEST(PointCloudToScan, VelodyneRingsAndTimesKept) {
  CapturedLog log;
  PointCloudToScan converter("/velodyne_points", LidarModel::kVlp16, PointFilter{});
  std::map<std::string, std::int64_t> dropped;
  const auto cloud = test::velodyneCloud(
      kStamp, {{5, 0, -1, 1, 0, 0.0f}, {5, 0, 1, 2, 15, 0.05f}, {0, 0, 0, 0, 0, 0}});
  const Scan scan = converter.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped);
  EXPECT_EQ(scan.stamp_ns, kStamp);
  EXPECT_EQ(scan.frame_id, "velodyne");
  ASSERT_EQ(scan.points.size(), 2u);
  EXPECT_EQ(scan.points[0].ring, 0);
  EXPECT_EQ(scan.points[1].ring, 15);
  EXPECT_EQ(scan.points[1].time, 0.05f);
  EXPECT_EQ(dropped[kDropPointNoReturn], 1);
  EXPECT_TRUE(log.warnings.empty());
}

TEST(PointCloudToScan, TopDownRingsAreRenumbered) {
  // Ouster organised cloud: 4 rows (ring 0 = top beam at +3 deg), 3 columns.
  std::vector<test::OusterPoint> points;
  for (std::uint16_t row = 0; row < 4; ++row) {
    for (int col = 0; col < 3; ++col) {
      const auto p = polar(10.0, -col * 0.1, (3.0 - 2.0 * row) * kDeg);
      points.push_back(
          {p[0], p[1], p[2], 100.0 + row, static_cast<std::uint32_t>(col * 1000), row});
    }
  }
  const auto cloud = test::ousterCloud(kStamp, 3, 4, points, test::OusterLayout::kLegacyRingU8);
  PointCloudToScan converter("/os_cloud_node/points", LidarModel::kOs1_64, PointFilter{});
  std::map<std::string, std::int64_t> dropped;
  const Scan scan = converter.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped);
  ASSERT_EQ(scan.points.size(), 12u);
  for (const auto& p : scan.points) {
    // Lowest beam (-3 deg, row 3, intensity 103) must be ring 0: ring = 3 - row.
    const int row = static_cast<int>(p.intensity) - 100;
    EXPECT_EQ(p.ring, 3 - row);
  }
  EXPECT_FLOAT_EQ(scan.points[1].time, 1e-6f);
}

TEST(PointCloudToScan, BottomUpRingsAreKept) {
  std::vector<test::HesaiPoint> points;
  for (std::uint16_t ring = 0; ring < 3; ++ring) {
    const auto p = polar(10.0, 0.2 * ring, (-2.0 + 2.0 * ring) * kDeg);
    points.push_back({p[0], p[1], p[2], 1.0f, 1'700'000'000.0, ring});
  }
  PointCloudToScan converter("/hesai/pandar", LidarModel::kGeneric, PointFilter{});
  std::map<std::string, std::int64_t> dropped;
  const auto cloud = test::hesaiCloud(kStamp, points);
  const Scan scan = converter.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped);
  ASSERT_EQ(scan.points.size(), 3u);
  for (std::uint16_t ring = 0; ring < 3; ++ring) EXPECT_EQ(scan.points[ring].ring, ring);
}

/// A VLP-16-like cloud without ring or time: 16 beams, `columns` azimuth steps, clockwise.
test::TestCloud xyzSweep(std::int64_t stamp_ns, int columns) {
  std::vector<std::vector<float>> xyz;
  for (int col = 0; col < columns; ++col) {
    for (int ring = 0; ring < 16; ++ring) {
      xyz.push_back(polar(8.0, 1.0 - 2.0 * M_PI * col / columns, (-15.0 + 2.0 * ring) * kDeg));
    }
  }
  return test::xyzCloud(stamp_ns, xyz);
}

TEST(PointCloudToScan, RingAndTimeDerivedWithOneWarning) {
  CapturedLog log;
  PointCloudToScan converter("/points", LidarModel::kVlp16, PointFilter{});
  std::map<std::string, std::int64_t> dropped;
  Scan scan;
  for (int k = 0; k < 3; ++k) {
    // Stamps 50 ms apart: a 20 Hz spin.
    const auto cloud = xyzSweep(kStamp + k * 50'000'000, 8);
    scan = converter.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped);
  }
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_NE(log.warnings[0].find("/points"), std::string::npos);
  EXPECT_NE(log.warnings[0].find("ring"), std::string::npos);
  EXPECT_NE(log.warnings[0].find("azimuth"), std::string::npos);
  EXPECT_DOUBLE_EQ(converter.periodSeconds(), 0.05);
  ASSERT_EQ(scan.points.size(), 8u * 16u);
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    EXPECT_EQ(scan.points[i].ring, i % 16) << i;
    const int col = static_cast<int>(i / 16);
    EXPECT_NEAR(scan.points[i].time, 0.05 * col / 8.0, 1e-6) << i;
  }
}

TEST(PointCloudToScan, GenericModelClustersElevations) {
  CapturedLog log;
  PointCloudToScan converter("/points", LidarModel::kGeneric, PointFilter{});
  std::map<std::string, std::int64_t> dropped;
  const auto cloud = xyzSweep(kStamp, 100);  // 1600 points: enough to fix the clusters
  const Scan scan = converter.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped);
  ASSERT_EQ(scan.points.size(), 1600u);
  for (std::size_t i = 0; i < scan.points.size(); ++i) ASSERT_EQ(scan.points[i].ring, i % 16) << i;
  EXPECT_NEAR(scan.points[16].time, 0.1 / 100.0, 1e-6);  // default period before two stamps
}

TEST(PointCloudToScan, WrongModelTableIsReported) {
  CapturedLog log;
  PointCloudToScan converter("/points", LidarModel::kHdl32e, PointFilter{});
  std::map<std::string, std::int64_t> dropped;
  // Beams at -30, -26, ... deg: half-way between entries of the HDL-32E table
  // (-30.67 + k 4/3 deg), as a VLP-16-like sensor would give.
  std::vector<std::vector<float>> xyz;
  for (int col = 0; col < 10; ++col) {
    for (int ring = 0; ring < 8; ++ring) {
      xyz.push_back(polar(8.0, -0.1 * col, (-30.0 + 4.0 * ring) * kDeg));
    }
  }
  const auto cloud = test::xyzCloud(kStamp, xyz);
  converter.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped);
  bool reported = false;
  for (const auto& w : log.warnings) reported |= w.find("HDL-32E laser table") != std::string::npos;
  EXPECT_TRUE(reported);
}

TEST(PointCloudToScan, DroppedPointsCountedByReason) {
  PointCloudToScan converter("/velodyne_points", LidarModel::kVlp16, PointFilter{1.0, 50.0});
  std::map<std::string, std::int64_t> dropped;
  const float nan = std::nanf("");
  const auto cloud = test::velodyneCloud(
      kStamp,
      {{nan, 0, 0, 0, 0, 0}, {0.5f, 0, 0, 0, 0, 0}, {60, 0, 0, 0, 0, 0}, {5, 0, 0, 0, 0, 0}});
  const Scan scan = converter.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped);
  EXPECT_EQ(scan.points.size(), 1u);
  EXPECT_EQ(dropped[kDropPointNotFinite], 1);
  EXPECT_EQ(dropped[kDropPointOutOfRange], 2);
}

TEST(PointCloudToScan, LayoutErrorsPropagate) {
  PointCloudToScan converter("/points", LidarModel::kVlp16, PointFilter{});
  std::map<std::string, std::int64_t> dropped;
  auto cloud = test::xyzCloud(kStamp, {{1, 2, 3}});
  cloud.fields.pop_back();  // no z
  EXPECT_THROW(converter.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped), Error);
}

}  // namespace
}  // namespace storey
