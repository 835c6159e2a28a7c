// Reading ROS1 bags written with the raw rosbag API: driver layouts decoded
// exactly, messages in time order, drops counted, topics chosen.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "common/error.h"
#include "common/log.h"
#include "config/config.h"
#include "io/log_reader.h"
#include "io/message_sequencer.h"
#include "io/point_cloud_to_scan.h"
#include "unit/io/bag_fixtures.h"

namespace storey {
namespace {

using test::TestBagWriter;
using test::TestImu;

constexpr std::int64_t kT0 = 1'700'000'000'000'000'000;
constexpr std::int64_t kMs = 1'000'000;

struct ReadResult {
  std::vector<Scan> scans;
  std::vector<ImuSample> imu;
  std::vector<std::int64_t> order_keys;  ///< delivery order: scan stamp + offset, IMU stamp
  LogReadStats stats;
  std::string description;
};

ReadResult readAll(const std::string& path, const Config& config = Config{}) {
  ReadResult out;
  const auto reader = openLog(path, config.input, config.sensor);
  out.description = reader->describe();
  LogMessage m;
  const std::int64_t offset_ns = secondsToNs(config.sensor.time_offset_lidar_to_imu);
  while (reader->next(m)) {
    if (auto* scan = std::get_if<Scan>(&m)) {
      out.order_keys.push_back(scan->stamp_ns + offset_ns);
      out.scans.push_back(std::move(*scan));
    } else {
      out.order_keys.push_back(std::get<ImuSample>(m).stamp_ns);
      out.imu.push_back(std::get<ImuSample>(m));
    }
  }
  out.stats = reader->stats();
  return out;
}

class BagReader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir("bag_reader");
    setLogSink([this](LogLevel level, const std::string& m) {
      if (level == LogLevel::kWarning) warnings_.push_back(m);
    });
  }
  void TearDown() override {
    setLogSink(nullptr);
    std::filesystem::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }

  /// A bag with `clouds` on /points (10 Hz, recorded 100 ms after their stamp) and 200 Hz IMU.
  std::string bagWithClouds(const std::string& name, const std::vector<test::TestCloud>& clouds) {
    const std::string file = path(name);
    TestBagWriter bag(file);
    for (int i = 0; i < 20 * static_cast<int>(clouds.size()) + 1; ++i) {
      TestImu imu;
      imu.stamp_ns = kT0 + i * 5 * kMs;
      bag.write("/imu", imu.stamp_ns + kMs, imu);
      for (const auto& c : clouds) {
        if (c.stamp_ns + 100 * kMs == imu.stamp_ns) bag.write("/points", imu.stamp_ns + kMs, c);
      }
    }
    bag.close();
    return file;
  }

  std::string dir_;
  std::vector<std::string> warnings_;
};

TEST_F(BagReader, VelodyneBagDecodedExactlyAndInTimeOrder) {
  test::VelodyneImuBag spec;
  const std::string file = path("velodyne.bag");
  test::writeVelodyneImuBag(file, spec);

  const ReadResult r = readAll(file);
  ASSERT_EQ(r.scans.size(), 10u);
  ASSERT_EQ(r.imu.size(), 200u);
  EXPECT_EQ(r.stats.scans, 10);
  EXPECT_EQ(r.stats.imu_samples, 200);
  EXPECT_EQ(r.stats.points, 640);
  EXPECT_TRUE(r.stats.dropped.empty());
  EXPECT_TRUE(std::is_sorted(r.order_keys.begin(), r.order_keys.end()));
  EXPECT_NE(r.description.find("/velodyne_points"), std::string::npos);
  EXPECT_NE(r.description.find("/imu/data"), std::string::npos);

  for (int s = 0; s < spec.scans; ++s) {
    const Scan& scan = r.scans[s];
    EXPECT_EQ(scan.stamp_ns, spec.start_ns + s * 100 * kMs);
    EXPECT_EQ(scan.frame_id, "velodyne");
    ASSERT_EQ(scan.points.size(), 64u);
    for (int k = 0; k < 64; ++k) {
      const test::VelodynePoint e = test::velodyneImuBagPoint(s, k, spec.points_per_scan);
      const ScanPoint& p = scan.points[k];
      ASSERT_EQ(p.p.x(), e.x);
      ASSERT_EQ(p.p.y(), e.y);
      ASSERT_EQ(p.p.z(), e.z);
      ASSERT_EQ(p.intensity, e.intensity);
      ASSERT_EQ(p.ring, e.ring);
      ASSERT_EQ(p.time, e.time);
    }
  }
  for (int i = 0; i < 200; ++i) {
    const TestImu e = test::velodyneImuBagImu(spec, i);
    EXPECT_EQ(r.imu[i].stamp_ns, e.stamp_ns);
    EXPECT_EQ(r.imu[i].gyro, e.gyro);
    EXPECT_EQ(r.imu[i].accel, e.accel);
  }
  // Scan s (stamp t) comes right after the IMU sample stamped t (IMU first at equal stamps).
  // Progress by record time: from 0 to 1, never backwards.
  std::size_t imu_seen = 0, scans_seen = 0;
  LogMessage m;
  const auto reader = openLog(file, InputConfig{}, SensorConfig{});
  EXPECT_EQ(reader->progress(), 0.0);
  double progress = 0.0;
  while (reader->next(m)) {
    EXPECT_GE(reader->progress(), progress);
    progress = reader->progress();
    if (std::holds_alternative<Scan>(m)) {
      EXPECT_EQ(imu_seen, scans_seen * 20 + 1) << "scan " << scans_seen;
      ++scans_seen;
    } else {
      ++imu_seen;
    }
  }
  EXPECT_GT(progress, 0.9);
  EXPECT_EQ(reader->progress(), 1.0);
}

TEST_F(BagReader, CompressedAndManyChunkBags) {
  for (const auto compression :
       {test::TestCompression::kLz4, test::TestCompression::kBz2, test::TestCompression::kNone}) {
    test::VelodyneImuBag spec;
    spec.compression = compression;
    spec.chunk_bytes = 4096;  // several chunks
    const std::string file =
        path("chunks" + std::to_string(static_cast<int>(compression)) + ".bag");
    test::writeVelodyneImuBag(file, spec);
    const ReadResult r = readAll(file);
    EXPECT_EQ(r.scans.size(), 10u);
    EXPECT_EQ(r.imu.size(), 200u);
    EXPECT_TRUE(std::is_sorted(r.order_keys.begin(), r.order_keys.end()));
    EXPECT_EQ(r.scans[3].points[5].p.x(), test::velodyneImuBagPoint(3, 5, 64).x);
  }
}

TEST_F(BagReader, OusterLayoutsRenumberTopDownRings) {
  for (const auto layout : {test::OusterLayout::kLegacyRingU8, test::OusterLayout::kRingU16,
                            test::OusterLayout::kLowDataIntensityU16}) {
    // 4 rows (row 0 = top beam at +3 deg) x 2 columns.
    std::vector<test::OusterPoint> points;
    for (std::uint16_t row = 0; row < 4; ++row) {
      for (int col = 0; col < 2; ++col) {
        const double elevation = (3.0 - 2.0 * row) * M_PI / 180.0;
        const double azimuth = -0.5 * col;
        points.push_back({static_cast<float>(10 * std::cos(elevation) * std::cos(azimuth)),
                          static_cast<float>(10 * std::cos(elevation) * std::sin(azimuth)),
                          static_cast<float>(10 * std::sin(elevation)), 200.0 + row,
                          static_cast<std::uint32_t>(col * 50'000'000), row});
      }
    }
    const std::string file =
        bagWithClouds("ouster" + std::to_string(static_cast<int>(layout)) + ".bag",
                      {test::ousterCloud(kT0, 2, 4, points, layout),
                       test::ousterCloud(kT0 + 100 * kMs, 2, 4, points, layout)});
    Config config;
    config.sensor.lidar_model = LidarModel::kOs1_64;
    const ReadResult r = readAll(file, config);
    ASSERT_EQ(r.scans.size(), 2u);
    ASSERT_EQ(r.scans[0].points.size(), 8u);
    for (std::size_t i = 0; i < 8; ++i) {
      const ScanPoint& p = r.scans[1].points[i];
      const auto& e = points[i];
      EXPECT_EQ(p.p, Eigen::Vector3f(e.x, e.y, e.z));
      EXPECT_EQ(p.intensity, static_cast<float>(e.intensity));
      EXPECT_EQ(p.ring, 3 - e.ring) << "ring 0 must be the lowest beam";
      EXPECT_EQ(p.time, static_cast<float>(e.t * 1e-9));
    }
  }
}

TEST_F(BagReader, HesaiAbsoluteTimestamps) {
  const double stamp_s = 1'700'000'000.0;
  const std::vector<test::HesaiPoint> points = {{4, 0, -0.5f, 12, stamp_s + 0.0, 0},
                                                {0, 4, 0.5f, 13, stamp_s + 0.046875, 1}};
  const std::string file = bagWithClouds("hesai.bag", {test::hesaiCloud(kT0, points)});
  const ReadResult r = readAll(file);
  ASSERT_EQ(r.scans.size(), 1u);
  ASSERT_EQ(r.scans[0].points.size(), 2u);
  EXPECT_EQ(r.scans[0].points[0].time, 0.0f);
  EXPECT_EQ(r.scans[0].points[1].time, 0.046875f);
  EXPECT_EQ(r.scans[0].points[1].intensity, 13.0f);
  EXPECT_EQ(r.scans[0].points[1].ring, 1);
  EXPECT_EQ(r.scans[0].frame_id, "PandarXT-32");
}

TEST_F(BagReader, CloudWithoutRingOrTimeDerivesThemWithOneWarning) {
  std::vector<test::TestCloud> clouds;
  for (int s = 0; s < 3; ++s) {
    std::vector<std::vector<float>> xyz;
    for (int col = 0; col < 4; ++col) {
      for (int ring = 0; ring < 16; ++ring) {
        const double elevation = (-15.0 + 2.0 * ring) * M_PI / 180.0;
        const double azimuth = -M_PI / 2 * col;
        xyz.push_back({static_cast<float>(6 * std::cos(elevation) * std::cos(azimuth)),
                       static_cast<float>(6 * std::cos(elevation) * std::sin(azimuth)),
                       static_cast<float>(6 * std::sin(elevation))});
      }
    }
    clouds.push_back(test::xyzCloud(kT0 + s * 100 * kMs, xyz));
  }
  const ReadResult r = readAll(bagWithClouds("xyz.bag", clouds));
  ASSERT_EQ(r.scans.size(), 3u);
  int derived_warnings = 0;
  for (const auto& w : warnings_) derived_warnings += w.find("/points: no 'ring' field") == 0;
  EXPECT_EQ(derived_warnings, 1);
  const Scan& scan = r.scans[2];
  ASSERT_EQ(scan.points.size(), 64u);
  for (int k = 0; k < 64; ++k) {
    EXPECT_EQ(scan.points[k].ring, k % 16);
    EXPECT_NEAR(scan.points[k].time, 0.1 * (k / 16) / 4.0, 1e-6);
    EXPECT_EQ(scan.points[k].intensity, 0.0f);
  }
}

TEST_F(BagReader, BigEndianCloud) {
  test::CloudBuilder builder(
      {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"ring", 12, 4, 1}, {"time", 14, 7, 1}}, 18,
      2, 1, /*big_endian=*/true);
  builder.set(0, "x", 3.5)
      .set(0, "y", -1.25)
      .set(0, "z", 0.5)
      .set(0, "ring", 7)
      .set(0, "time", 0.015625);
  builder.set(1, "x", -2)
      .set(1, "y", 6)
      .set(1, "z", -0.75)
      .set(1, "ring", 2)
      .set(1, "time", 0.03125);
  const ReadResult r = readAll(bagWithClouds("big_endian.bag", {builder.build(kT0)}));
  ASSERT_EQ(r.scans.size(), 1u);
  ASSERT_EQ(r.scans[0].points.size(), 2u);
  EXPECT_EQ(r.scans[0].points[0].p, Eigen::Vector3f(3.5f, -1.25f, 0.5f));
  EXPECT_EQ(r.scans[0].points[0].ring, 7);
  EXPECT_EQ(r.scans[0].points[0].time, 0.015625f);
  EXPECT_EQ(r.scans[0].points[1].p, Eigen::Vector3f(-2.0f, 6.0f, -0.75f));
  EXPECT_EQ(r.scans[0].points[1].ring, 2);
}

TEST_F(BagReader, NanAndOutOfRangePointsDroppedAndCounted) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto cloud = test::velodyneCloud(kT0, {{nan, nan, nan, 0, 0, 0},
                                               {1, 1, nan, 0, 0, 0},
                                               {0.1f, 0, 0, 0, 0, 0},
                                               {500, 0, 0, 0, 0, 0},
                                               {0, 0, 0, 0, 0, 0},
                                               {3, 4, 0, 9, 4, 0.01f}});
  const ReadResult r = readAll(bagWithClouds("nan.bag", {cloud}));
  ASSERT_EQ(r.scans.size(), 1u);
  ASSERT_EQ(r.scans[0].points.size(), 1u);
  EXPECT_EQ(r.scans[0].points[0].p, Eigen::Vector3f(3, 4, 0));
  EXPECT_EQ(r.stats.dropped.at(kDropPointNotFinite), 2);
  EXPECT_EQ(r.stats.dropped.at(kDropPointOutOfRange), 2);  // default range [0.3, 120] m
  EXPECT_EQ(r.stats.dropped.at(kDropPointNoReturn), 1);
  EXPECT_EQ(r.stats.points, 1);
}

TEST_F(BagReader, OutOfOrderImuPutInOrderAndCounted) {
  const std::string file = path("imu_order.bag");
  {
    TestBagWriter bag(file);
    const std::int64_t stamps_ms[] = {0, 5, 10, 7, 10, 15, 20, 3, 25};
    std::int64_t record = kT0;
    for (const std::int64_t ms : stamps_ms) {
      TestImu imu;
      imu.stamp_ns = kT0 + ms * kMs;
      bag.write("/imu", record += kMs, imu);
    }
    TestImu nan_imu;
    nan_imu.stamp_ns = kT0 + 30 * kMs;
    nan_imu.gyro.x() = std::numeric_limits<double>::quiet_NaN();
    bag.write("/imu", record += kMs, nan_imu);
    TestImu no_gyro;
    no_gyro.stamp_ns = kT0 + 35 * kMs;
    no_gyro.gyro_missing = true;
    bag.write("/imu", record += kMs, no_gyro);
    bag.write("/points", record += kMs, test::velodyneCloud(kT0, {{5, 0, 0, 1, 0, 0}}));
  }
  const ReadResult r = readAll(file);
  std::vector<std::int64_t> stamps_ms;
  for (const auto& s : r.imu) stamps_ms.push_back((s.stamp_ns - kT0) / kMs);
  // 7 and 3 were recorded late: put back in order (within the reorder window).
  EXPECT_EQ(stamps_ms, (std::vector<std::int64_t>{0, 3, 5, 7, 10, 15, 20, 25}));
  EXPECT_EQ(r.stats.reordered, 2);
  EXPECT_EQ(r.stats.dropped.count(kDropImuBackwards), 0u);
  EXPECT_EQ(r.stats.dropped.at(kDropImuDuplicate), 1);
  EXPECT_EQ(r.stats.dropped.at(kDropImuNotFinite), 1);
  EXPECT_EQ(r.stats.dropped.at(kDropImuMissingData), 1);
  EXPECT_TRUE(std::is_sorted(r.order_keys.begin(), r.order_keys.end()));
}

TEST_F(BagReader, TimeOffsetOrdersScansInTheImuClock) {
  test::VelodyneImuBag spec;
  const std::string file = path("offset.bag");
  test::writeVelodyneImuBag(file, spec);
  Config config;
  config.sensor.time_offset_lidar_to_imu = 0.0125;  // 12.5 ms: between IMU samples (5 ms apart)
  const ReadResult r = readAll(file, config);
  ASSERT_EQ(r.scans.size(), 10u);
  EXPECT_EQ(r.scans[0].stamp_ns, spec.start_ns);  // raw stamp kept
  EXPECT_TRUE(std::is_sorted(r.order_keys.begin(), r.order_keys.end()));
  // IMU at 0, 5, 10 ms come before the first scan (12.5 ms in the IMU clock).
  std::size_t imu_before = 0;
  const auto reader = openLog(file, config.input, config.sensor);
  LogMessage m;
  while (reader->next(m) && !std::holds_alternative<Scan>(m)) ++imu_before;
  EXPECT_EQ(imu_before, 3u);
}

TEST_F(BagReader, TopicsAutoDetectedByTypeAndOverridable) {
  const std::string file = path("topics.bag");
  {
    TestBagWriter bag(file);
    for (int i = 0; i < 40; ++i) {
      TestImu imu;
      imu.stamp_ns = kT0 + i * 5 * kMs;
      bag.write("/imu/fast", imu.stamp_ns, imu);
      if (i % 2 == 0) bag.write("/imu/slow", imu.stamp_ns, imu);
      if (i % 20 == 0) {
        bag.write("/lidar/a", imu.stamp_ns + kMs,
                  test::velodyneCloud(imu.stamp_ns, {{5, 0, 0, 1, 0, 0}}));
        bag.write("/lidar/b", imu.stamp_ns + kMs,
                  test::velodyneCloud(imu.stamp_ns, {{5, 0, 0, 1, 0, 0}, {6, 0, 0, 1, 0, 0}}));
      }
      if (i % 10 == 0)
        bag.write("/lidar/b", imu.stamp_ns + 2 * kMs,
                  test::xyzCloud(imu.stamp_ns + kMs, {{7, 0, 0}}));
      if (i == 3) bag.writeString("/notes", imu.stamp_ns, "hello");
    }
  }
  const ReadResult automatic = readAll(file);
  EXPECT_NE(automatic.description.find("/lidar/b"), std::string::npos);  // 6 messages vs 2
  EXPECT_NE(automatic.description.find("/imu/fast"), std::string::npos);
  EXPECT_EQ(automatic.imu.size(), 40u);
  bool warned = false;
  for (const auto& w : warnings_) warned |= w.find("/imu/slow") != std::string::npos;
  EXPECT_TRUE(warned);

  Config config;
  config.input.points_topic = "/lidar/a";
  config.input.imu_topic = "/imu/slow";
  const ReadResult chosen = readAll(file, config);
  EXPECT_EQ(chosen.imu.size(), 20u);
  EXPECT_EQ(chosen.scans.size(), 2u);
  EXPECT_NE(chosen.description.find("/lidar/a"), std::string::npos);
}

/// Points (x y z intensity) of a binary PCD file with those four float32 fields.
std::vector<std::array<float, 4>> readXyziPcd(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t points = 0;
  while (std::getline(in, line)) {
    if (line.rfind("FIELDS", 0) == 0 && line != "FIELDS x y z intensity") return {};
    if (line.rfind("POINTS ", 0) == 0) points = std::stoul(line.substr(7));
    if (line.rfind("DATA", 0) == 0) break;
  }
  if (line != "DATA binary") return {};
  std::vector<std::array<float, 4>> xyzi(points);
  in.read(reinterpret_cast<char*>(xyzi.data()), static_cast<std::streamsize>(points * 16));
  return in ? xyzi : std::vector<std::array<float, 4>>{};
}

TEST_F(BagReader, RealHdl32eScanWithoutRingOrTime) {
  // A real HDL-32E scan (fast_gicp sample, x y z intensity only) in a bag:
  // rings from the HDL-32E laser table and from clustering must agree, cover
  // the 32 lasers, and number them from the lowest elevation.
  const std::string pcd = std::string(STOREY_REAL_DATA_DIR) + "/fast_gicp-scan-pair/251370668.pcd";
  if (!std::filesystem::exists(pcd)) GTEST_SKIP() << "real data absent: " << pcd;
  const auto xyzi = readXyziPcd(pcd);
  ASSERT_EQ(xyzi.size(), 69088u);
  test::CloudBuilder builder(
      {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"intensity", 12, 7, 1}}, 16,
      static_cast<std::uint32_t>(xyzi.size()));
  std::size_t expected_points = 0;
  for (std::uint32_t i = 0; i < xyzi.size(); ++i) {
    const auto& p = xyzi[i];
    builder.set(i, "x", p[0]).set(i, "y", p[1]).set(i, "z", p[2]).set(i, "intensity", p[3]);
    const double range = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    expected_points += std::isfinite(range) && range >= 0.3 && range <= 120.0;
  }
  const std::string file = bagWithClouds("hdl32e.bag", {builder.build(kT0)});

  Config table_config;
  table_config.sensor.lidar_model = LidarModel::kHdl32e;
  Config generic_config;
  generic_config.sensor.lidar_model = LidarModel::kGeneric;
  const ReadResult by_table = readAll(file, table_config);
  const ReadResult by_clusters = readAll(file, generic_config);
  ASSERT_EQ(by_table.scans.size(), 1u);
  ASSERT_EQ(by_clusters.scans.size(), 1u);
  const auto& a = by_table.scans[0].points;
  const auto& b = by_clusters.scans[0].points;
  ASSERT_EQ(a.size(), expected_points);
  ASSERT_EQ(b.size(), expected_points);
  std::set<std::uint16_t> rings;
  std::vector<double> lowest_elevation(32, 10.0), highest_elevation(32, -10.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].ring, b[i].ring) << i;
    ASSERT_LT(a[i].ring, 32);
    ASSERT_GE(a[i].time, 0.0f);
    ASSERT_LT(a[i].time, 0.1f);
    rings.insert(a[i].ring);
    const double e = std::atan2(a[i].p.z(), a[i].p.head<2>().norm());
    lowest_elevation[a[i].ring] = std::min(lowest_elevation[a[i].ring], e);
    highest_elevation[a[i].ring] = std::max(highest_elevation[a[i].ring], e);
  }
  EXPECT_EQ(rings.size(), 32u);
  for (int r = 0; r + 1 < 32; ++r) EXPECT_LT(highest_elevation[r], lowest_elevation[r + 1]) << r;
  EXPECT_NEAR(lowest_elevation[0] * 180 / M_PI, -30.67, 0.1);
  EXPECT_EQ(a[0].intensity, xyzi[0][3]);
}

}  // namespace
}  // namespace storey
