#include "common/error.h"
#include "io/log_format.h"
#include "io/log_reader.h"
#include "io/pcd_folder_reader.h"
#include "io/rosbag_reader.h"
#include "io/velodyne/velodyne_pcap_reader.h"

namespace storey {

std::unique_ptr<LogReader> openLog(const std::string& path, const Config& config) {
  switch (detectLogFormat(path)) {
    case LogFormat::kRosbag1:
      return openRosbagLog(path, config);
    case LogFormat::kVelodynePcap:
      return openVelodynePcapLog(path, config);
    case LogFormat::kPcdFolder:
      return openPcdFolderLog(path, config);
  }
  throw Error(path + ": unknown log format");
}

}  // namespace storey
