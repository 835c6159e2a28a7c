// The sensor calibration file (io/calibration_file.h), read as
// `storey run --calibration FILE` does (over a configuration).
#include "config/config.h"
#include "fuzz_common.h"
#include "io/calibration_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "calibration.yaml");
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::readCalibrationFile(path); });
  storey::fuzz::expectOnlyStoreyErrors([&] {
    storey::Config config;
    storey::applyCalibrationFile(config, path);
    config.validate();
  });
  return 0;
}
