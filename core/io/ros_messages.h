#pragma once
/// The ROS messages Storey reads, as plain types (no ROS headers): what the
/// ROS1 bag, rosbag2 (sqlite3) and MCAP readers hand to the point cloud,
/// IMU and Velodyne packet decoding, whatever the container and encoding.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/point_cloud_layout.h"
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
  bool is_dense = true;
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

/// Bytes of one Velodyne data packet (velodyne_msgs/VelodynePacket.data).
inline constexpr std::size_t kVelodynePacketBytes = 1206;

/// One velodyne_msgs/VelodynePacket: the time the driver received it and its UDP payload.
struct VelodynePacketMessage {
  std::int64_t stamp_ns = 0;  ///< [ns]
  std::array<std::uint8_t, kVelodynePacketBytes> data{};
};

/// A velodyne_msgs/VelodyneScan: the packets of (about) one revolution.
struct VelodyneScanMessage {
  std::int64_t stamp_ns = 0;  ///< header stamp [ns]
  std::string frame_id;
  std::vector<VelodynePacketMessage> packets;
};

/// ROS message type names (ROS 1 spelling; ROS 2's "pkg/msg/Type" is
/// normalised to "pkg/Type" by canonicalRosType).
inline constexpr const char* kPointCloud2Type = "sensor_msgs/PointCloud2";
inline constexpr const char* kImuType = "sensor_msgs/Imu";
inline constexpr const char* kVelodyneScanType = "velodyne_msgs/VelodyneScan";

/// "sensor_msgs/msg/PointCloud2" -> "sensor_msgs/PointCloud2"; other names unchanged.
std::string canonicalRosType(const std::string& type);

}  // namespace storey
