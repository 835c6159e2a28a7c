#pragma once
/// Writes simulated scans and IMU samples to a ROS1 bag in the layout of the
/// Velodyne ROS driver (sensor_msgs/PointCloud2: x y z intensity float32 at
/// offsets 0 4 8 16, ring uint16 at 20, time float32 at 24 [s from the header
/// stamp], point_step 32) and sensor_msgs/Imu. No ROS types in this header.
#include <cstdint>
#include <memory>
#include <string>

#include "types/imu_sample.h"
#include "types/scan.h"

namespace storey::sim {

enum class BagCompression { kNone, kLz4 };

class BagWriter {
 public:
  /// Opens `path` for writing (truncates). Throws storey::Error.
  BagWriter(const std::string& path, BagCompression compression);
  ~BagWriter();
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  /// Scan with an absolute stamp; `receipt_ns` is the bag (record) time.
  void writeScan(const std::string& topic, const Scan& scan, std::int64_t receipt_ns);
  /// IMU sample with an absolute stamp (also its record time). Covariances are
  /// the discrete white-noise variances; orientation is not provided
  /// (orientation_covariance[0] = -1).
  void writeImu(const std::string& topic, const std::string& frame_id, const ImuSample& sample,
                double gyro_variance, double accel_variance);
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
};

}  // namespace storey::sim
