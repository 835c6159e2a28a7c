// VeloView calibration XML (input.velodyne_calibration), for the model the
// input's size picks.
#include "fuzz_common.h"
#include "io/velodyne/velodyne_tables.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "calibration.xml");
  const auto model = static_cast<storey::velodyne::Model>(size % 3);
  storey::fuzz::expectOnlyStoreyErrors(
      [&] { storey::velodyne::readVeloViewCalibration(path, model); });
  return 0;
}
