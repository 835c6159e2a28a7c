// ROS 1 bag: the structure checks (io/rosbag_structure.h), then the reader
// the program opens (openLog: librosbag, PointCloud2 / Imu / VelodyneScan decoding).
#include "fuzz_common.h"
#include "io/rosbag_structure.h"
#include "log_drain.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "input.bag");
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::checkRosbagStructure(path); });
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::fuzz::openAndDrainLog(path); });
  return 0;
}
