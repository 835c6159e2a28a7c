#include "common/error.h"
#include "io/log_format.h"
#include "io/log_reader.h"
#include "io/pcd_folder_reader.h"
#include "io/rosbag_reader.h"
#include "io/velodyne/velodyne_pcap_reader.h"

namespace storey {

std::unique_ptr<LogReader> openLog(const std::string& path, const InputConfig& input,
                                   const SensorConfig& sensor) {
  switch (detectLogFormat(path)) {
    case LogFormat::kRosbag1:
      return openRosbagLog(path, input, sensor);
    case LogFormat::kVelodynePcap:
      return openVelodynePcapLog(path, input, sensor);
    case LogFormat::kPcdFolder:
      return openPcdFolderLog(path, input, sensor);
    case LogFormat::kRos2Sqlite:
    case LogFormat::kMcap:
      return openRos2Log(path, input, sensor);
  }
  throw Error(path + ": unknown log format");
}

}  // namespace storey
