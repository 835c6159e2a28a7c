#pragma once
/// Test point clouds in the exact byte layouts of real LiDAR drivers, as plain
/// types (no ROS): a layout (fields, point_step) plus bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "io/point_cloud_layout.h"

namespace storey::test {

/// A sensor_msgs/PointCloud2 to decode or to write into a bag.
struct TestCloud {
  std::int64_t stamp_ns = 0;
  std::string frame_id = "lidar";
  std::vector<PointFieldDesc> fields;
  std::uint32_t height = 1;
  std::uint32_t width = 0;
  std::uint32_t point_step = 0;
  std::uint32_t row_step = 0;
  bool is_bigendian = false;
  std::vector<std::uint8_t> data;

  PointCloudView view() const;
};

/// Fills the bytes of a cloud field by field through its descriptors,
/// converting each value to the field's datatype and byte order. Padding
/// bytes (not covered by a field) are filled with 0xEE so that a decoder
/// reading them would see garbage.
class CloudBuilder {
 public:
  CloudBuilder(std::vector<PointFieldDesc> fields, std::uint32_t point_step, std::uint32_t width,
               std::uint32_t height = 1, bool big_endian = false, std::uint32_t row_padding = 0);
  /// Sets field `name` of point `index` (row-major) to `value`.
  CloudBuilder& set(std::uint32_t index, const std::string& name, double value);
  TestCloud build(std::int64_t stamp_ns) const;

 private:
  TestCloud cloud_;
};

/// Velodyne driver (velodyne_pointcloud) point, point_step 32.
struct VelodynePoint {
  float x, y, z, intensity;
  std::uint16_t ring;
  float time;  ///< [s] relative to the header stamp
};
/// Bytes written by hand at the driver's offsets: x y z float32 at 0/4/8,
/// 4 padding bytes, intensity float32 at 16, ring uint16 at 20, 2 padding
/// bytes, time float32 at 24, point_step 32 (8 trailing padding bytes).
TestCloud velodyneCloud(std::int64_t stamp_ns, const std::vector<VelodynePoint>& points);

/// Ouster point (organised clouds, ring 0 = top beam as the driver numbers rows).
struct OusterPoint {
  float x, y, z;
  double intensity;
  std::uint32_t t;  ///< [ns] relative to the header stamp
  std::uint16_t ring;
};
enum class OusterLayout {
  kLegacyRingU8,  ///< ouster_ros 1.x: intensity f32@16, t u32@20, reflectivity u16@24, ring u8@26,
                  ///< ambient u16@28, range u32@32, step 48
  kRingU16,       ///< ouster-ros 0.x: same offsets, ring u16@26
  kLowDataIntensityU16,  ///< x y z f32, t u32@12, intensity u16@16, ring u16@18, step 20
};
TestCloud ousterCloud(std::int64_t stamp_ns, std::uint32_t width, std::uint32_t height,
                      const std::vector<OusterPoint>& points_row_major, OusterLayout layout);

/// Hesai (HesaiLidar_General_ROS) point: x y z f32 0/4/8, intensity f32@16,
/// timestamp f64@24 (ABSOLUTE seconds), ring u16@32, point_step 48.
struct HesaiPoint {
  float x, y, z, intensity;
  double timestamp;  ///< [s] absolute
  std::uint16_t ring;
};
TestCloud hesaiCloud(std::int64_t stamp_ns, const std::vector<HesaiPoint>& points);

/// x y z (float32) only: no ring, no time, no intensity; point_step 12.
TestCloud xyzCloud(std::int64_t stamp_ns, const std::vector<std::vector<float>>& xyz);

}  // namespace storey::test
