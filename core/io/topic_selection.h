#pragma once
/// Choice of the point cloud and IMU topics of a log: by message type, the
/// busiest topic of each type unless the configuration names one.
#include <cstdint>
#include <string>
#include <vector>

#include "io/input_config.h"
#include "io/ros_messages.h"
#include "types/sensor.h"

namespace storey {

/// One topic of a log.
struct TopicInfo {
  std::string name;
  std::string type;        ///< as stored, e.g. "sensor_msgs/Imu" or "sensor_msgs/msg/Imu"
  std::int64_t count = 0;  ///< messages
};

struct TopicChoice {
  std::string points_topic;
  std::string points_type = kPointCloud2Type;  ///< canonical: PointCloud2 or VelodyneScan
  std::string imu_topic;
};

/// Picks input.points_topic / input.imu_topic when set (error if absent from
/// the log or of another type), else the topic of the right type with the
/// most messages (ties: the first by name), logging a warning that names the
/// others. The LiDAR topic is a sensor_msgs/PointCloud2 topic, or when there
/// is none a velodyne_msgs/VelodyneScan (packets) topic. Types compare in
/// their canonical spelling (ROS 2's "pkg/msg/Type" = "pkg/Type"). Throws storey::Error naming
/// `file` and listing the topics found when the log has no point cloud or no IMU topic.
TopicChoice chooseTopics(const std::vector<TopicInfo>& topics, const InputConfig& input,
                         const std::string& file);

/// "/a (sensor_msgs/Imu, 400 messages), /b (...)" or "none".
std::string describeTopics(const std::vector<TopicInfo>& topics);

}  // namespace storey
