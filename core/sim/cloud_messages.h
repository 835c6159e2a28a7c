#pragma once
/// The simulator's point clouds as sensor_msgs/PointCloud2 (plain
/// io::PointCloudMessage), in the layouts of the Velodyne and Ouster ROS
/// drivers, for every log writer.
#include <cstdint>
#include <string>

#include "io/ros_messages.h"
#include "sim/organised_scan.h"
#include "types/scan.h"

namespace storey::sim {

/// The point fields of the Ouster ROS driver's cloud (ouster-ros, the
/// "original" point type): name, byte offset, sensor_msgs/PointField datatype.
struct CloudField {
  const char* name;
  std::uint32_t offset;
  std::uint8_t datatype;
};
inline constexpr CloudField kOusterFields[] = {
    {"x", 0, 7},          {"y", 4, 7},        {"z", 8, 7},
    {"intensity", 16, 7}, {"t", 20, 6},       {"reflectivity", 24, 4},
    {"ring", 26, 4},      {"ambient", 28, 4}, {"range", 32, 6}};
inline constexpr std::uint32_t kOusterPointStep = 48;

/// The Velodyne driver's layout: x y z intensity float32 at offsets 0 4 8 16,
/// ring uint16 at 20, time float32 at 24 [s from the header stamp], point_step 32.
PointCloudMessage velodyneLayoutCloud(const Scan& scan);

/// The Ouster driver's layout: height = rows (row r = ring r, 0 = the top
/// beam), width = columns, kOusterFields, point_step 48 (zero padding), `t` =
/// ns after the header stamp, `range` in mm, `ambient` 0; no-returns are zero
/// points kept in place (is_dense true, as the driver sets it).
PointCloudMessage ousterLayoutCloud(const OrganisedScan& scan, const std::string& frame_id,
                                    std::int64_t stamp_ns);

}  // namespace storey::sim
