// Choice of the point cloud and IMU topics.
#include "io/topic_selection.h"

#include <gtest/gtest.h>

#include "common/error.h"
#include "common/log.h"

namespace storey {
namespace {

const std::vector<TopicInfo> kTopics = {
    {"/imu/data", kImuType, 4000},
    {"/imu/raw", kImuType, 8000},
    {"/ouster/points", kPointCloud2Type, 100},
    {"/rosout", "rosgraph_msgs/Log", 12},
    {"/velodyne_points", kPointCloud2Type, 100},
};

std::string errorOf(const std::vector<TopicInfo>& topics, const InputConfig& input) {
  try {
    chooseTopics(topics, input, "/data/run.bag");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(IoTopicSelection, BusiestTopicOfEachTypeWithWarning) {
  std::vector<std::string> warnings;
  setLogSink([&](LogLevel level, const std::string& m) {
    if (level == LogLevel::kWarning) warnings.push_back(m);
  });
  const TopicChoice choice = chooseTopics(kTopics, InputConfig{}, "/data/run.bag");
  setLogSink(nullptr);
  EXPECT_EQ(choice.imu_topic, "/imu/raw");
  EXPECT_EQ(choice.points_topic, "/ouster/points");  // tie: first by name
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("/velodyne_points"), std::string::npos);
  EXPECT_NE(warnings[1].find("/imu/data"), std::string::npos);
}

TEST(IoTopicSelection, OverridesWin) {
  InputConfig input;
  input.points_topic = "/velodyne_points";
  input.imu_topic = "/imu/data";
  const TopicChoice choice = chooseTopics(kTopics, input, "/data/run.bag");
  EXPECT_EQ(choice.points_topic, "/velodyne_points");
  EXPECT_EQ(choice.imu_topic, "/imu/data");
}

TEST(IoTopicSelection, ErrorsNameTheFileAndListTopics) {
  InputConfig missing;
  missing.points_topic = "/nope";
  const std::string no_topic = errorOf(kTopics, missing);
  EXPECT_NE(no_topic.find("/data/run.bag"), std::string::npos) << no_topic;
  EXPECT_NE(no_topic.find("/nope does not exist"), std::string::npos) << no_topic;
  EXPECT_NE(no_topic.find("/rosout (rosgraph_msgs/Log, 12 messages)"), std::string::npos);

  InputConfig wrong_type;
  wrong_type.imu_topic = "/velodyne_points";
  EXPECT_NE(errorOf(kTopics, wrong_type).find("is not of type sensor_msgs/Imu"), std::string::npos);

  const std::vector<TopicInfo> no_imu = {{"/velodyne_points", kPointCloud2Type, 10}};
  const std::string e1 = errorOf(no_imu, InputConfig{});
  EXPECT_NE(e1.find("no IMU topic"), std::string::npos) << e1;
  EXPECT_NE(e1.find("/velodyne_points (sensor_msgs/PointCloud2, 10 messages)"), std::string::npos);

  const std::string e2 = errorOf({}, InputConfig{});
  EXPECT_NE(e2.find("no point cloud topic"), std::string::npos) << e2;
  EXPECT_NE(e2.find("topics found: none"), std::string::npos) << e2;
  EXPECT_EQ(e2.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace storey
