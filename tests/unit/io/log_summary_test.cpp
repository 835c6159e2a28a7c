// Log summaries (`storey info`): per-topic type, count, rate, duration,
// stamps, and for point clouds the fields and points per message.
#include "io/log_summary.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/error.h"
#include "common/log.h"
#include "unit/io/bag_fixtures.h"

namespace storey {
namespace {

constexpr std::int64_t kT0 = 1'700'000'000'000'000'000;
constexpr std::int64_t kMs = 1'000'000;

class LogSummaryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir("log_summary");
    setLogSink([](LogLevel, const std::string&) {});
  }
  void TearDown() override {
    setLogSink(nullptr);
    std::filesystem::remove_all(dir_);
  }
  std::string dir_;
};

const TopicSummary& topic(const LogSummary& s, const std::string& name) {
  for (const auto& t : s.topics) {
    if (t.name == name) return t;
  }
  throw std::runtime_error("no topic " + name);
}

TEST_F(LogSummaryTest, VelodyneBagWithOtherTopics) {
  const std::string file = dir_ + "/summary.bag";
  {
    test::TestBagWriter bag(file, test::TestCompression::kLz4);
    // IMU at 200 Hz for 1 s (201 samples), clouds of 3, 5 and 4 points at 10 Hz
    // recorded 100 ms late, a String topic without header twice.
    for (int i = 0; i <= 200; ++i) {
      test::TestImu imu;
      imu.stamp_ns = kT0 + i * 5 * kMs;
      bag.write("/imu/data", imu.stamp_ns + kMs, imu);
    }
    const int sizes[] = {3, 5, 4};
    for (int s = 0; s < 3; ++s) {
      std::vector<test::VelodynePoint> points(sizes[s], test::VelodynePoint{5, 0, 0, 1, 0, 0});
      bag.write("/velodyne_points", kT0 + (s + 1) * 100 * kMs,
                test::velodyneCloud(kT0 + s * 100 * kMs, points));
    }
    bag.writeString("/notes", kT0 + 250 * kMs, "a");
    bag.writeString("/notes", kT0 + 750 * kMs, "b");
  }

  const LogSummary s = summarizeLog(file, InputConfig{});
  EXPECT_EQ(s.path, file);
  EXPECT_EQ(s.format, "ROS1 bag 2.0");
  EXPECT_EQ(s.compression, "lz4");
  EXPECT_EQ(s.messages, 201 + 3 + 2);
  EXPECT_EQ(s.start_ns, kT0 + kMs);
  EXPECT_EQ(s.end_ns, kT0 + 1001 * kMs);
  EXPECT_EQ(s.points_topic, "/velodyne_points");
  EXPECT_EQ(s.imu_topic, "/imu/data");
  EXPECT_TRUE(s.input_problem.empty());
  ASSERT_EQ(s.topics.size(), 3u);
  EXPECT_EQ(s.topics[0].name, "/imu/data");  // sorted by name
  EXPECT_EQ(s.topics[1].name, "/notes");

  const TopicSummary& imu = topic(s, "/imu/data");
  EXPECT_EQ(imu.type, "sensor_msgs/Imu");
  EXPECT_EQ(imu.count, 201);
  EXPECT_TRUE(imu.header_stamps);
  EXPECT_EQ(imu.first_stamp_ns, kT0);
  EXPECT_EQ(imu.last_stamp_ns, kT0 + 1000 * kMs);
  EXPECT_DOUBLE_EQ(imu.durationSeconds(), 1.0);
  EXPECT_DOUBLE_EQ(imu.rateHz(), 200.0);
  EXPECT_TRUE(imu.fields.empty());

  const TopicSummary& cloud = topic(s, "/velodyne_points");
  EXPECT_EQ(cloud.type, "sensor_msgs/PointCloud2");
  EXPECT_EQ(cloud.count, 3);
  EXPECT_EQ(cloud.first_stamp_ns, kT0);  // header stamps, not record times
  EXPECT_EQ(cloud.last_stamp_ns, kT0 + 200 * kMs);
  EXPECT_NEAR(cloud.rateHz(), 10.0, 1e-9);
  EXPECT_EQ(cloud.points_min, 3);
  EXPECT_EQ(cloud.points_median, 4);
  EXPECT_EQ(cloud.points_max, 5);
  EXPECT_EQ(cloud.point_step, 32u);
  EXPECT_FALSE(cloud.layout_varies);
  const std::vector<PointFieldDesc> expected_fields = {{"x", 0, 7, 1},     {"y", 4, 7, 1},
                                                       {"z", 8, 7, 1},     {"intensity", 16, 7, 1},
                                                       {"ring", 20, 4, 1}, {"time", 24, 7, 1}};
  EXPECT_EQ(cloud.fields, expected_fields);

  const TopicSummary& notes = topic(s, "/notes");
  EXPECT_EQ(notes.type, "std_msgs/String");
  EXPECT_FALSE(notes.header_stamps);  // record times
  EXPECT_EQ(notes.first_stamp_ns, kT0 + 250 * kMs);
  EXPECT_EQ(notes.last_stamp_ns, kT0 + 750 * kMs);
  EXPECT_DOUBLE_EQ(notes.rateHz(), 2.0);
}

TEST_F(LogSummaryTest, LogWithoutImuIsSummarisedWithTheProblem) {
  const std::string file = dir_ + "/no_imu.bag";
  {
    test::TestBagWriter bag(file);
    bag.write("/points", kT0, test::xyzCloud(kT0, {{1, 2, 3}}));
  }
  const LogSummary s = summarizeLog(file, InputConfig{});
  ASSERT_EQ(s.topics.size(), 1u);
  EXPECT_EQ(s.topics[0].count, 1);
  EXPECT_EQ(s.topics[0].rateHz(), 0.0);
  EXPECT_NE(s.input_problem.find("no IMU topic"), std::string::npos) << s.input_problem;
}

TEST_F(LogSummaryTest, ProgressAndCancel) {
  const std::string file = dir_ + "/progress.bag";
  test::VelodyneImuBag spec;
  spec.scans = 60;  // 1200 IMU samples: one progress report before the end
  test::writeVelodyneImuBag(file, spec);
  int calls = 0;
  summarizeLog(file, InputConfig{}, [&](double fraction, const std::string&) {
    EXPECT_GE(fraction, 0.0);
    EXPECT_LE(fraction, 1.0);
    ++calls;
    return true;
  });
  EXPECT_GE(calls, 2);
  EXPECT_THROW(summarizeLog(file, InputConfig{}, [](double, const std::string&) { return false; }),
               Cancelled);
}

}  // namespace
}  // namespace storey
