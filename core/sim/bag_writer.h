#pragma once
/// Writes simulated scans and IMU samples to a ROS1 bag: point clouds in the
/// layout of the Velodyne or the Ouster ROS driver (sim/cloud_messages.h),
/// sensor_msgs/Imu, and Velodyne packets as velodyne_msgs/VelodyneScan. No
/// ROS types in this header.
#include <cstdint>
#include <memory>
#include <string>

#include "sim/cloud_messages.h"
#include "sim/sim_log_writer.h"

namespace storey::sim {

enum class BagCompression { kNone, kLz4 };

class BagWriter final : public SimLogWriter {
 public:
  /// Opens `path` for writing (truncates). Throws storey::Error.
  BagWriter(const std::string& path, BagCompression compression);
  ~BagWriter() override;
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

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
  void writeCloud(const std::string& topic, const PointCloudMessage& cloud,
                  std::int64_t receipt_ns);

  struct Impl;
  /// Keeps a bag whose writing failed from ever being destroyed (see the .cpp).
  static void abandon(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  std::string path_;
};

}  // namespace storey::sim
