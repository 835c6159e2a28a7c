// rosbag2's metadata.yaml (io/rosbag2_metadata.h).
#include "io/rosbag2_metadata.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "metadata.yaml");
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::readRosbag2Metadata(path); });
  return 0;
}
