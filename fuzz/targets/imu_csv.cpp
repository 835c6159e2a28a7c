// IMU CSV (io/imu_csv.h): the header, then every sample.
#include "io/imu_csv.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "imu.csv");
  storey::fuzz::expectOnlyStoreyErrors([&] {
    storey::ImuCsvReader reader(path, 250000000);
    storey::ImuSample sample;
    while (reader.next(sample)) {
    }
    reader.progress();
  });
  return 0;
}
