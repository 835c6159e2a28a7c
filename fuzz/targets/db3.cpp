// rosbag2 sqlite3 storage (.db3): the storage layer (every row), then the
// reader the program opens (openLog: CDR decoding, scans and IMU samples).
#include "fuzz_common.h"
#include "io/ros2_storage.h"
#include "io/sqlite_storage.h"
#include "log_drain.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "input.db3");
  storey::fuzz::expectOnlyStoreyErrors([&] {
    auto storage = storey::openSqliteStorage({path});
    storage->properties();
    storage->select({});
    storey::RawMessage message;
    while (storage->next(message)) {
    }
  });
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::fuzz::openAndDrainLog(path); });
  return 0;
}
