// Velodyne capture (pcap / pcapng): the reader the program opens
// (VelodynePcapReader: libpcap, link layers, IP/UDP, packet decoding and
// frame assembly), without requiring an IMU source. Odd sizes read any port.
#include "fuzz_common.h"
#include "io/velodyne/velodyne_pcap_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "input.pcap");
  storey::fuzz::expectOnlyStoreyErrors([&] {
    storey::VelodynePcapOptions options;
    options.require_imu = false;
    if (size % 2 == 1) {
      options.data_port = 0;
      options.position_port = 0;
    }
    storey::VelodynePcapReader reader(path, options);
    storey::LogMessage message;
    while (reader.next(message)) {
    }
    reader.describe();
    reader.imuSource();
  });
  return 0;
}
