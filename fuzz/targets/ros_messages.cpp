// ROS message decoding (io/ros_message_codec.h, io/ros_wire.h) in ROS 1
// serialization and CDR: byte 0 picks the format and the message type
// (sensor_msgs/Imu, velodyne_msgs/VelodyneScan -> VelodyneScanDecoder, a
// header stamp), the rest is the message. PointCloud2 has its own target.
#include <map>
#include <vector>

#include "fuzz_common.h"
#include "io/ros_message_codec.h"
#include "io/velodyne/velodyne_scan_decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  if (size < 1) return 0;
  const storey::WireFormat format =
      (data[0] & 1) ? storey::WireFormat::kCdr : storey::WireFormat::kRos1;
  const int kind = (data[0] >> 1) % 3;
  const std::uint8_t* body = data + 1;
  const std::size_t body_size = size - 1;
  storey::fuzz::expectOnlyStoreyErrors([&] {
    if (kind == 0) {
      storey::decodeImu(body, body_size, format);
    } else if (kind == 1) {
      storey::VelodyneScanMessage scan;
      storey::decodeVelodyneScan(body, body_size, format, scan);
      storey::VelodyneScanDecoder decoder("fuzz.bag /velodyne_packets",
                                          storey::VelodyneScanOptions{});
      std::vector<storey::Scan> done;
      std::map<std::string, std::int64_t> dropped;
      decoder.add(scan, done, dropped);
      decoder.add(scan, done, dropped);  // the same packets again: not newer
      decoder.flush(done);
    } else {
      storey::decodeHeaderStamp(body, body_size, format);
    }
  });
  return 0;
}
