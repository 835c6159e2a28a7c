#pragma once
/// A ROS 2 bag as a RosMessageSource: a rosbag2 folder (metadata.yaml with
/// sqlite3 .db3 or .mcap files), a folder of .db3 files without metadata,
/// a single .db3 file, or a single MCAP file. Messages are decoded from
/// their encoding ("cdr", or "ros1" in MCAP files converted from ROS 1 bags).
#include <memory>
#include <string>

#include "io/ros_message_source.h"

namespace storey {

/// Whether `dir` looks like a rosbag2 folder (metadata.yaml, or .db3 / .mcap files).
bool isRos2BagFolder(const std::string& dir);

/// Opens the bag. Throws storey::Error naming the file for an unreadable,
/// damaged or unsupported bag (file-compressed rosbag2, a storage other than
/// sqlite3 and MCAP).
std::unique_ptr<RosMessageSource> openRos2Bag(const std::string& path);

}  // namespace storey
