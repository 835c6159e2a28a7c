#pragma once
/// Recognises a log's format from its content (never from its file name).
#include <string>

namespace storey {

enum class LogFormat {
  kRosbag1,        ///< ROS1 bag, format 2.0
  kVelodynePcap,   ///< pcap or pcapng capture (Velodyne UDP packets)
  kPcdFolder,      ///< a folder of PCD scans (one per scan)
};

/// First line of a ROS1 bag in format 2.0.
inline constexpr const char* kRosbag2Magic = "#ROSBAG V2.0\n";

/// Short name of a format, e.g. "ROS1 bag 2.0".
const char* toString(LogFormat format);

/// Detects the format of the log at `path` by its first bytes: a ROS1 bag
/// ("#ROSBAG V2.0"), a capture (pcap magic 0xA1B2C3D4 / 0xA1B23C4D either
/// byte order, or pcapng), or a folder holding PCD files (their header read).
/// Throws storey::Error naming the path when it is missing, unreadable, empty,
/// a ROS bag of another version, a folder without PCD scans, or of no known format.
LogFormat detectLogFormat(const std::string& path);

}  // namespace storey
