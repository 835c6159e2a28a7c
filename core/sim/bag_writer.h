#pragma once
/// Writes simulated scans and IMU samples to a ROS1 bag: point clouds in the
/// layout of the Velodyne ROS driver (sensor_msgs/PointCloud2: x y z intensity
/// float32 at offsets 0 4 8 16, ring uint16 at 20, time float32 at 24 [s from
/// the header stamp], point_step 32) or of the Ouster ROS driver (organised,
/// see writeOrganisedScan), and sensor_msgs/Imu. No ROS types in this header.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>

#include "sim/organised_scan.h"
#include "types/imu_sample.h"
#include "types/scan.h"

namespace storey::sim {

enum class BagCompression { kNone, kLz4 };

/// The orientation an IMU reports with a sample.
struct ImuOrientation {
  Eigen::Quaterniond q_world_imu = Eigen::Quaterniond::Identity();
  Eigen::Vector3d variance = Eigen::Vector3d::Zero();  ///< about x, y, z [rad^2]
};

/// The point fields of the Ouster ROS driver's cloud (ouster-ros, the
/// "original" point type): name, byte offset, sensor_msgs/PointField datatype.
struct CloudField {
  const char* name;
  std::uint32_t offset;
  std::uint8_t datatype;
};
inline constexpr CloudField kOusterFields[] = {
    {"x", 0, 7},          {"y", 4, 7},        {"z", 8, 7},
    {"intensity", 16, 7}, {"t", 20, 6},       {"reflectivity", 24, 4},
    {"ring", 26, 4},      {"ambient", 28, 4}, {"range", 32, 6}};
inline constexpr std::uint32_t kOusterPointStep = 48;

class BagWriter {
 public:
  /// Opens `path` for writing (truncates). Throws storey::Error.
  BagWriter(const std::string& path, BagCompression compression);
  ~BagWriter();
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  /// Scan with an absolute stamp; `receipt_ns` is the bag (record) time.
  void writeScan(const std::string& topic, const Scan& scan, std::int64_t receipt_ns);
  /// An organised scan in the Ouster ROS driver's layout: height = rows
  /// (row r = ring r, 0 = the top beam), width = columns, kOusterFields,
  /// point_step 48 (zero padding), `t` = ns after the header stamp, `range` in
  /// mm, `ambient` 0; no-returns are zero points kept in place (is_dense true,
  /// as the driver sets it). `stamp_ns` is absolute.
  void writeOrganisedScan(const std::string& topic, const std::string& frame_id,
                          const OrganisedScan& scan, std::int64_t stamp_ns,
                          std::int64_t receipt_ns);
  /// IMU sample with an absolute stamp (also its record time). Covariances are
  /// the discrete white-noise variances. Without `orientation` none is
  /// provided (orientation_covariance[0] = -1; the quaternion left at identity).
  void writeImu(const std::string& topic, const std::string& frame_id, const ImuSample& sample,
                double gyro_variance, double accel_variance,
                const ImuOrientation* orientation = nullptr);
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
};

}  // namespace storey::sim
