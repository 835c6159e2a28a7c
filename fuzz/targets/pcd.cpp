// PCD file (ascii, binary, binary_compressed): readPcd, then its points
// through PointCloudToScan, as the PCD folder reader does.
#include <map>

#include "fuzz_common.h"
#include "io/pcd_file.h"
#include "io/point_cloud_to_scan.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "input.pcd");
  storey::fuzz::expectOnlyStoreyErrors([&] {
    const storey::PcdCloud cloud = storey::readPcd(path);
    storey::PointCloudToScan clouds(path, storey::LidarModel::kGeneric, storey::PointFilter{});
    std::map<std::string, std::int64_t> dropped;
    clouds.convert(cloud.view(), 1700000000000000000, "pcd", dropped);
  });
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::readPcdHeader(path); });
  return 0;
}
