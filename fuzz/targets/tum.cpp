// TUM trajectories (trajectory/tum.h), as `storey eval` reads ground truth.
#include "trajectory/tum.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "input.tum");
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::readTum(path); });
  return 0;
}
