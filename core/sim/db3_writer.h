#pragma once
/// Writes rosbag2's sqlite3 storage (.db3), schema version 3 as ROS 2 Humble
/// writes it: tables schema, metadata, topics and messages.
#include <memory>
#include <string>

#include "sim/ros2_storage_writer.h"

namespace storey::sim {

/// Creates `path` (replacing it). Throws storey::Error naming the file.
std::unique_ptr<Ros2StorageWriter> openDb3Writer(const std::string& path);

}  // namespace storey::sim
