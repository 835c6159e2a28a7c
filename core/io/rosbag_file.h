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
#include "io/rosbag_structure.h"
#include "io/topic_selection.h"
#include "types/imu_sample.h"

namespace storey {

/// A sensor_msgs/PointCloud2 without ROS types; owns its bytes.
struct PointCloudMessage {
  std::int64_t stamp_ns = 0;  ///< header stamp [ns]
  std::string frame_id;
  std::vector<PointFieldDesc> fields;
  std::uint32_t height = 0;
  std::uint32_t width = 0;
  std::uint32_t point_step = 0;
  std::uint32_t row_step = 0;
  bool is_bigendian = false;
  std::vector<std::uint8_t> data;

  /// A view of this message's layout and bytes (valid while the message lives).
  PointCloudView view() const;
};

/// A sensor_msgs/Imu reduced to what the pipeline uses (orientation ignored).
struct ImuMessage {
  ImuSample sample;       ///< header stamp, angular_velocity, linear_acceleration
  bool has_gyro = true;   ///< false when angular_velocity_covariance[0] == -1 ("no data")
  bool has_accel = true;  ///< false when linear_acceleration_covariance[0] == -1
};

class RosbagFile {
 public:
  /// Checks the file's structure (checkRosbagStructure), then opens it with
  /// librosbag and lists its topics. Throws storey::Error naming the file.
  explicit RosbagFile(const std::string& path);
  ~RosbagFile();
  RosbagFile(const RosbagFile&) = delete;
  RosbagFile& operator=(const RosbagFile&) = delete;

  const std::string& path() const;
  const RosbagStructure& structure() const;
  /// Every (topic, type) of the bag with its message count, sorted by topic.
  const std::vector<TopicInfo>& topics() const;
  /// Whether messages of `topic` start with a std_msgs/Header (from the message definition).
  bool hasHeader(const std::string& topic) const;

  /// Starts iterating over the messages of `topics` (every topic when empty),
  /// in record-time order, lazily: one message in memory at a time.
  void select(const std::vector<std::string>& topics);
  /// Advances to the next selected message; false at the end.
  bool next();
  /// Earliest and latest record time of the selected messages [ns] (0 when none).
  std::int64_t selectionBeginNs() const;
  std::int64_t selectionEndNs() const;

  // The current message (after next() returned true).
  const std::string& topic() const;
  const std::string& type() const;
  std::int64_t recordTimeNs() const;
  std::int64_t indexInTopic() const;  ///< 0-based position of the message within its topic
  /// "FILE: TOPIC message #N (record time S s)", the prefix of errors about this message.
  std::string where() const;

  /// Deserialises the current message as sensor_msgs/PointCloud2 into `out`.
  void readPointCloud(PointCloudMessage& out) const;
  /// Deserialises the current message as sensor_msgs/Imu.
  ImuMessage readImu() const;
  /// The header stamp of the current message when its type starts with a
  /// std_msgs/Header (reads only the header's first bytes), else nullopt.
  std::optional<std::int64_t> readHeaderStamp() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace storey
