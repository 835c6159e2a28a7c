#pragma once
/// Recognises a log's format from its content (never from its file name).
#include <string>

namespace storey {

enum class LogFormat {
  kRosbag1,       ///< ROS1 bag, format 2.0
  kVelodynePcap,  ///< pcap or pcapng capture (Velodyne UDP packets)
  kPcdFolder,     ///< a folder of PCD scans (one per scan)
  kRos2Sqlite,    ///< rosbag2: a folder with metadata.yaml / .db3 files, or a .db3 file
  kMcap,          ///< an MCAP file, or a rosbag2 folder of MCAP storage
};

/// First line of a ROS1 bag in format 2.0.
inline constexpr const char* kRosbag2Magic = "#ROSBAG V2.0\n";

/// Short name of a format, e.g. "ROS1 bag 2.0".
const char* toString(LogFormat format);

/// Detects the format of the log at `path` by its first bytes: a ROS1 bag
/// ("#ROSBAG V2.0"), a capture (pcap magic 0xA1B2C3D4 / 0xA1B23C4D either
/// byte order, or pcapng), an MCAP file (0x89 "MCAP0\r\n"), a sqlite3
/// database ("SQLite format 3"), a rosbag2 folder (metadata.yaml, .db3 or
/// .mcap files), or a folder holding PCD files (their header read).
/// Throws storey::Error naming the path when it is missing, unreadable, empty,
/// a ROS bag of another version, a folder without PCD scans, or of no known format.
LogFormat detectLogFormat(const std::string& path);

/// The log a user means by choosing `chosen` in a file dialog (which can
/// pick files only): a rosbag2 folder's metadata.yaml or a PCD file of a PCD
/// folder stands for its folder; any other path is itself.
std::string logPathForChosenFile(const std::string& chosen);

/// File dialog filter of the logs Storey reads (Qt syntax).
inline constexpr const char* kLogFileDialogFilter =
    "Logs (*.bag *.pcap *.pcapng *.db3 *.mcap metadata.yaml *.pcd);;All files (*)";

}  // namespace storey
