#pragma once
/// A log of ROS messages, whatever its container (ROS1 bag, rosbag2 sqlite3
/// folder, MCAP): its topics, and its messages one at a time in record order,
/// decoded on demand into the plain message types of io/ros_messages.h.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/ros_messages.h"
#include "io/topic_selection.h"

namespace storey {

class RosMessageSource {
 public:
  virtual ~RosMessageSource() = default;

  virtual const std::string& path() const = 0;
  /// e.g. "ROS1 bag 2.0", "rosbag2 (sqlite3)", "MCAP".
  virtual std::string formatName() const = 0;
  /// What `storey info` shows about the container, as (name, value) lines.
  virtual std::vector<std::pair<std::string, std::string>> properties() const { return {}; }
  virtual std::uint64_t sizeBytes() const = 0;
  /// Every (topic, type) with its message count, sorted by topic. Types as
  /// stored (ROS 2: "sensor_msgs/msg/Imu"); compare with canonicalRosType.
  virtual const std::vector<TopicInfo>& topics() const = 0;
  /// Whether messages of `topic` start with a std_msgs/Header.
  virtual bool hasHeader(const std::string& topic) const = 0;
  /// Total messages (for progress).
  virtual std::int64_t messageCount() const;

  /// Starts iterating over the messages of `topics` (every topic when empty).
  virtual void select(const std::vector<std::string>& topics) = 0;
  /// Advances to the next selected message; false at the end.
  virtual bool next() = 0;
  /// Earliest and latest record time of the selected messages [ns] (0 when unknown).
  virtual std::int64_t selectionBeginNs() const = 0;
  virtual std::int64_t selectionEndNs() const = 0;

  // The current message (after next() returned true).
  virtual const std::string& topic() const = 0;
  virtual const std::string& type() const = 0;
  virtual std::int64_t recordTimeNs() const = 0;
  virtual std::int64_t indexInTopic() const = 0;
  /// "FILE: TOPIC message #N (record time S s)", the prefix of errors about this message.
  virtual std::string where() const = 0;

  virtual void readPointCloud(PointCloudMessage& out) const = 0;
  virtual ImuMessage readImu() const = 0;
  virtual void readVelodyneScan(VelodyneScanMessage& out) const = 0;
  /// The header stamp when the current message's type starts with a Header, else nullopt.
  virtual std::optional<std::int64_t> readHeaderStamp() const = 0;
};

/// True when the first declaration of a message definition (ROS 1 .msg or
/// ros2msg text) is a std_msgs/Header.
bool definitionStartsWithHeader(const std::string& definition);

/// "%.6f" seconds of `ns`.
std::string formatSecondsNs(std::int64_t ns);

}  // namespace storey
