#pragma once
/// The storage layer of a ROS 2 bag being written: sqlite3 (.db3) or MCAP.
#include <cstdint>
#include <string>
#include <vector>

namespace storey::sim {

class Ros2StorageWriter {
 public:
  virtual ~Ros2StorageWriter() = default;
  /// Declares a topic (ids from 1, in order); `type` in ROS 2 spelling
  /// ("sensor_msgs/msg/Imu"), `definition` its ros2msg text.
  virtual void addTopic(int id, const std::string& name, const std::string& type,
                        const std::string& definition) = 0;
  /// One CDR-serialized message of topic `id` recorded at `log_time_ns`.
  virtual void write(int id, std::int64_t log_time_ns, const std::vector<std::uint8_t>& data) = 0;
  /// Completes the file; throws storey::Error naming it when it cannot be written.
  virtual void close() = 0;
};

}  // namespace storey::sim
