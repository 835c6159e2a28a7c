// MCAP (io/mcap_file.h): the storage layer (every record, chunks none / zstd /
// lz4, CRCs), then the reader the program opens (openLog: CDR or ROS 1 decoding).
#include "fuzz_common.h"
#include "io/mcap_file.h"
#include "io/ros2_storage.h"
#include "log_drain.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "input.mcap");
  storey::fuzz::expectOnlyStoreyErrors([&] {
    auto storage = storey::openMcapStorage(path);
    storage->properties();
    storage->select({});
    storey::RawMessage message;
    while (storage->next(message)) {
    }
  });
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::fuzz::openAndDrainLog(path); });
  return 0;
}
