#pragma once
/// A ROS1 bag read through librosbag, with its messages converted to plain
/// types. This is the adapter at the edge: ROS types stay in its .cpp file.
/// Every failure of librosbag is translated into a storey::Error naming the
/// file (and the topic, message index and record time when reading a message).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/point_cloud_layout.h"
#include "io/ros_message_source.h"
#include "io/rosbag_structure.h"
#include "io/topic_selection.h"
#include "types/imu_sample.h"

namespace storey {

class RosbagFile final : public RosMessageSource {
 public:
  /// Checks the file's structure (checkRosbagStructure), then opens it with
  /// librosbag and lists its topics. Throws storey::Error naming the file.
  explicit RosbagFile(const std::string& path);
  ~RosbagFile() override;
  RosbagFile(const RosbagFile&) = delete;
  RosbagFile& operator=(const RosbagFile&) = delete;

  const std::string& path() const override;
  const RosbagStructure& structure() const;
  /// Every (topic, type) of the bag with its message count, sorted by topic.
  const std::vector<TopicInfo>& topics() const override;
  /// Whether messages of `topic` start with a std_msgs/Header (from the message definition).
  bool hasHeader(const std::string& topic) const override;

  /// Starts iterating over the messages of `topics` (every topic when empty),
  /// in record-time order, lazily: one message in memory at a time.
  void select(const std::vector<std::string>& topics) override;
  /// Advances to the next selected message; false at the end.
  bool next() override;
  /// Earliest and latest record time of the selected messages [ns] (0 when none).
  std::int64_t selectionBeginNs() const override;
  std::int64_t selectionEndNs() const override;

  // The current message (after next() returned true).
  const std::string& topic() const override;
  const std::string& type() const override;
  std::int64_t recordTimeNs() const override;
  std::int64_t indexInTopic() const override;  ///< 0-based position of the message within its topic
  /// "FILE: TOPIC message #N (record time S s)", the prefix of errors about this message.
  std::string where() const override;

  /// Deserialises the current message as sensor_msgs/PointCloud2 into `out`.
  void readPointCloud(PointCloudMessage& out) const override;
  /// Deserialises the current message as sensor_msgs/Imu.
  ImuMessage readImu() const override;
  /// The header stamp of the current message when its type starts with a
  /// std_msgs/Header (reads only the header's first bytes), else nullopt.
  std::optional<std::int64_t> readHeaderStamp() const override;
  /// Deserialises the current message as velodyne_msgs/VelodyneScan (from its raw bytes).
  void readVelodyneScan(VelodyneScanMessage& out) const override;

  std::string formatName() const override { return "ROS1 bag 2.0"; }
  std::vector<std::pair<std::string, std::string>> properties() const override;
  std::uint64_t sizeBytes() const override;
  std::int64_t messageCount() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace storey
