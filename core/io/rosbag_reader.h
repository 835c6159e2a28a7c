#pragma once
/// LogReader for ROS logs (ROS1 bags, rosbag2 sqlite3 folders and MCAP
/// files): sensor_msgs/PointCloud2 scans, or velodyne_msgs/VelodyneScan
/// packets decoded into scans, and sensor_msgs/Imu samples, streamed in time
/// order (see docs/formats.md, "Input: ROS1 bags" and "Input: ROS 2 bags").
#include <memory>
#include <string>

#include "io/input_config.h"
#include "io/log_reader.h"
#include "io/ros_message_source.h"
#include "types/sensor.h"

namespace storey {

/// Opens a ROS1 bag (format 2.0). Topics come from input or are
/// auto-detected by type; sensor.lidar_model and sensor.time_offset_lidar_to_imu
/// are used for rings and ordering, input.min_range / max_range to drop points.
/// Throws storey::Error naming the file when it cannot be read or lacks point
/// clouds or IMU.
std::unique_ptr<LogReader> openRosbagLog(const std::string& path, const InputConfig& input,
                                         const SensorConfig& sensor);

/// The same for a ROS 2 bag (io/ros2_bag.h: folder, .db3 or .mcap).
std::unique_ptr<LogReader> openRos2Log(const std::string& path, const InputConfig& input,
                                       const SensorConfig& sensor);

/// The same over any source of ROS messages.
std::unique_ptr<LogReader> openRosLog(std::unique_ptr<RosMessageSource> source,
                                      const InputConfig& input, const SensorConfig& sensor);

}  // namespace storey
