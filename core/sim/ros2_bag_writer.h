#pragma once
/// Writes the simulated log as a ROS 2 bag: a rosbag2 folder with
/// metadata.yaml (format version 5) and one storage file, sqlite3 (.db3) or
/// MCAP (.mcap, chunks none/zstd/lz4 compressed), messages CDR-serialized
/// (sensor_msgs/msg/PointCloud2, sensor_msgs/msg/Imu, velodyne_msgs/msg/VelodyneScan).
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "sim/mcap_writer.h"
#include "sim/sim_log_writer.h"

namespace storey::sim {

enum class Ros2Storage { kSqlite3, kMcap };

class Ros2BagWriter final : public SimLogWriter {
 public:
  /// Creates the folder `dir` (its stem names the storage file).
  Ros2BagWriter(const std::string& dir, Ros2Storage storage, const McapWriterOptions& mcap = {});
  ~Ros2BagWriter() override;

  void writeScan(const std::string& topic, const Scan& scan, std::int64_t receipt_ns) override;
  void writeOrganisedScan(const std::string& topic, const std::string& frame_id,
                          const OrganisedScan& scan, std::int64_t stamp_ns,
                          std::int64_t receipt_ns) override;
  void writeImu(const std::string& topic, const std::string& frame_id, const ImuSample& sample,
                std::int64_t record_ns, double gyro_variance, double accel_variance,
                const ImuOrientation* orientation = nullptr) override;
  void writeVelodyneScan(const std::string& topic, const VelodyneScanMessage& scan,
                         std::int64_t receipt_ns) override;
  void close() override;

 private:
  void write(const std::string& topic, const char* canonical_type, std::int64_t log_time_ns,
             const std::vector<std::uint8_t>& data);

  struct TopicState {
    int id = 0;
    std::string type;  ///< ROS 2 spelling
    std::int64_t count = 0;
  };
  std::string dir_;
  Ros2Storage storage_;
  std::string file_name_;
  std::unique_ptr<Ros2StorageWriter> writer_;
  std::map<std::string, TopicState> topics_;
  std::int64_t messages_ = 0;
  std::int64_t first_ns_ = 0, last_ns_ = 0;
  bool closed_ = false;
};

}  // namespace storey::sim
