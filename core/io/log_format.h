#pragma once
/// Recognises a log's format from its content (never from its file name).
#include <string>

namespace storey {

enum class LogFormat {
  kRosbag1,  ///< ROS1 bag, format 2.0
};

/// First line of a ROS1 bag in format 2.0.
inline constexpr const char* kRosbag2Magic = "#ROSBAG V2.0\n";

/// Detects the format of the file at `path` by its first bytes. Throws
/// storey::Error naming the file when it is missing, not a regular file,
/// unreadable, empty, a ROS bag of another version, or of no known format.
LogFormat detectLogFormat(const std::string& path);

}  // namespace storey
