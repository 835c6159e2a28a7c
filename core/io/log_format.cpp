#include "io/log_format.h"

#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/mcap_file.h"
#include "io/pcd_folder_reader.h"
#include "io/ros2_bag.h"
#include "io/rosbag2_metadata.h"
#include "io/sqlite_storage.h"
#include "io/velodyne/pcap_file.h"

namespace storey {

const char* toString(LogFormat format) {
  switch (format) {
    case LogFormat::kRosbag1:
      return "ROS1 bag 2.0";
    case LogFormat::kVelodynePcap:
      return "Velodyne pcap";
    case LogFormat::kPcdFolder:
      return "PCD folder";
    case LogFormat::kRos2Sqlite:
      return "rosbag2 (sqlite3)";
    case LogFormat::kMcap:
      return "MCAP";
  }
  return "unknown";
}

std::string logPathForChosenFile(const std::string& chosen) {
  const std::filesystem::path p(chosen);
  if (p.filename() == kRosbag2MetadataFile || p.extension() == ".pcd") {
    const std::string folder = p.parent_path().empty() ? "." : p.parent_path().string();
    return folder;
  }
  return chosen;
}

LogFormat detectLogFormat(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw Error(path + ": no such file");
  if (fs::is_directory(status)) {
    if (isRos2BagFolder(path)) {
      const fs::path metadata = fs::path(path) / kRosbag2MetadataFile;
      if (fs::exists(metadata) &&
          readRosbag2Metadata(metadata.string()).storage_identifier == "mcap") {
        return LogFormat::kMcap;
      }
      bool any_db3 = false;
      for (const auto& entry : fs::directory_iterator(path, ec)) {
        any_db3 = any_db3 || entry.path().extension() == ".db3";
      }
      if (!any_db3 && !fs::exists(metadata)) return LogFormat::kMcap;
      return LogFormat::kRos2Sqlite;
    }
    findPcdScans(path);  // throws when the folder holds no PCD scan
    return LogFormat::kPcdFolder;
  }
  if (!fs::is_regular_file(status)) throw Error(path + ": not a regular file");

  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the file for reading");
  char head[64] = {};
  in.read(head, sizeof(head));
  const auto n = static_cast<std::size_t>(in.gcount());
  if (n == 0) throw Error(path + ": empty file");

  const std::string start(head, n);
  if (start.rfind(kRosbag2Magic, 0) == 0) return LogFormat::kRosbag1;
  const std::string rosbag_prefix = "#ROSBAG V";
  if (start.rfind(rosbag_prefix, 0) == 0) {
    const std::size_t end = start.find_first_of("\r\n", rosbag_prefix.size());
    const std::string version =
        start.substr(rosbag_prefix.size(), std::min<std::size_t>(end, 16) - rosbag_prefix.size());
    throw Error(path + ": unsupported ROS bag version '" + version + "' (Storey reads 2.0)");
  }
  if (n < std::strlen(kRosbag2Magic) && std::string(kRosbag2Magic).rfind(start, 0) == 0) {
    throw Error(path + ": truncated ROS bag (" + std::to_string(n) + " bytes)");
  }
  if (isMcapMagic(start)) return LogFormat::kMcap;
  if (n < kMcapMagicSize && std::string(kMcapMagic, kMcapMagicSize).rfind(start, 0) == 0) {
    throw Error(path + ": truncated MCAP file (" + std::to_string(n) + " bytes)");
  }
  if (isSqliteHeader(start)) return LogFormat::kRos2Sqlite;
  if (velodyne::isPcapMagic(start)) {
    if (n < 24)
      throw Error(path + ": truncated pcap file (" + std::to_string(n) +
                  " bytes, header needs 24)");
    return LogFormat::kVelodynePcap;
  }
  if (start.rfind("# .PCD", 0) == 0 || start.rfind("VERSION", 0) == 0 ||
      start.rfind("FIELDS", 0) == 0) {
    throw Error(path + ": a single PCD file; give the folder holding the scans (one PCD per scan)");
  }
  throw Error(path +
              ": unknown log format (expected a ROS1 bag starting with '#ROSBAG V2.0', a ROS 2 bag "
              "(rosbag2 folder, .db3 or MCAP file), a pcap/pcapng capture of Velodyne packets, or "
              "a folder of PCD scans)");
}

}  // namespace storey
