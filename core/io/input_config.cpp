#include "io/input_config.h"

#include "common/error.h"

namespace storey {

namespace {

void require(bool ok, const std::string& key, const std::string& what) {
  if (!ok) throw Error("key '" + key + "' " + what);
}

}  // namespace

void InputConfig::validate() const {
  require(min_range >= 0.0, "input.min_range", "must be >= 0");
  require(max_range > min_range, "input.max_range", "must be larger than 'input.min_range'");
  require(velodyne_model == "auto" || velodyne_model == "VLP-16" || velodyne_model == "HDL-32E",
          "input.velodyne_model", "must be auto, VLP-16 or HDL-32E");
  require(pcap_clock == "sensor" || pcap_clock == "capture", "input.pcap_clock",
          "must be sensor or capture");
  require(pcap_data_port >= 0 && pcap_data_port <= 65535, "input.pcap_data_port",
          "must be a UDP port (0 = any)");
  require(pcap_position_port >= 0 && pcap_position_port <= 65535, "input.pcap_position_port",
          "must be a UDP port (0 = any)");
}

}  // namespace storey
