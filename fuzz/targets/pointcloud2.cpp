// sensor_msgs/PointCloud2 bytes (byte 0: wire format and LiDAR model, then
// the message) -> decodePointCloud2 -> PointCloudToScan, as the bag readers do.
#include <map>

#include "fuzz_common.h"
#include "io/point_cloud_to_scan.h"
#include "io/ros_message_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  if (size < 1) return 0;
  const storey::WireFormat format =
      (data[0] & 1) ? storey::WireFormat::kCdr : storey::WireFormat::kRos1;
  const auto model = static_cast<storey::LidarModel>((data[0] >> 1) % 5);
  storey::fuzz::expectOnlyStoreyErrors([&] {
    storey::PointCloudMessage cloud;
    storey::decodePointCloud2(data + 1, size - 1, format, cloud);
    storey::PointCloudToScan clouds("/points", model, storey::PointFilter{});
    std::map<std::string, std::int64_t> dropped;
    clouds.convert(cloud.view(), cloud.stamp_ns, cloud.frame_id, dropped);
    // A second cloud of the same topic: the cached layout and ring order.
    clouds.convert(cloud.view(), cloud.stamp_ns + 100000000, cloud.frame_id, dropped);
  });
  return 0;
}
