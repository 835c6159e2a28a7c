#pragma once
/// LogReader for ROS1 bags: sensor_msgs/PointCloud2 scans and sensor_msgs/Imu
/// samples, streamed in time order (see docs/formats.md, "Input: ROS1 bags").
#include <memory>
#include <string>

#include "io/input_config.h"
#include "io/log_reader.h"
#include "types/sensor.h"

namespace storey {

/// Opens a ROS1 bag (format 2.0). Topics come from input or are
/// auto-detected by type; sensor.lidar_model and sensor.time_offset_lidar_to_imu
/// are used for rings and ordering, input.min_range / max_range to drop points.
/// Throws storey::Error naming the file when it cannot be read or lacks point
/// clouds or IMU.
std::unique_ptr<LogReader> openRosbagLog(const std::string& path, const InputConfig& input,
                                         const SensorConfig& sensor);

}  // namespace storey
