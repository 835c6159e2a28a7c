#include "io/log_format.h"

#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/pcd_folder_reader.h"
#include "io/velodyne/pcap_file.h"

namespace storey {

const char* toString(LogFormat format) {
  switch (format) {
    case LogFormat::kRosbag1: return "ROS1 bag 2.0";
    case LogFormat::kVelodynePcap: return "Velodyne pcap";
    case LogFormat::kPcdFolder: return "PCD folder";
  }
  return "unknown";
}

LogFormat detectLogFormat(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw Error(path + ": no such file");
  if (fs::is_directory(status)) {
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
  if (velodyne::isPcapMagic(start)) {
    if (n < 24) throw Error(path + ": truncated pcap file (" + std::to_string(n) + " bytes, header needs 24)");
    return LogFormat::kVelodynePcap;
  }
  if (start.rfind("# .PCD", 0) == 0 || start.rfind("VERSION", 0) == 0 ||
      start.rfind("FIELDS", 0) == 0) {
    throw Error(path + ": a single PCD file; give the folder holding the scans (one PCD per scan)");
  }
  throw Error(path +
              ": unknown log format (expected a ROS1 bag starting with '#ROSBAG V2.0', a pcap/pcapng "
              "capture of Velodyne packets, or a folder of PCD scans)");
}

}  // namespace storey
