#pragma once
/// Decoding of PointCloud2 bytes into ScanPoints, driven only by the field
/// descriptors (name, offset, datatype, count): no layout is assumed.
///
/// Fields read (first match wins):
///   position   x, y, z (required)
///   intensity  intensity, else reflectivity, else i
///   ring       ring
///   time       time   seconds (float) or ns (integer), relative to the header stamp (Velodyne)
///              t      ns (integer) or seconds (float), relative (Ouster)
///              offset_time  as t (Livox)
///              timestamp    absolute when its value exceeds 1e6 s (Hesai float64 seconds;
///                           integer or > 1e15 values are ns), else relative
/// Any of the eight datatypes is accepted for any field; big-endian data is swapped.
#include <cstdint>
#include <string>
#include <vector>

#include "io/point_cloud_layout.h"
#include "types/scan.h"

namespace storey {

/// How a cloud's time field relates to the header stamp.
enum class PointTimeReference {
  kRelative,  ///< value is an offset from the header stamp
  kAbsolute,  ///< value is an absolute time (same clock as the header stamp)
  kDetect,    ///< absolute if the cloud's first finite value exceeds 1e6 s, else relative
};

/// Where one quantity lives in a point.
struct FieldSlot {
  bool present = false;
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
};

/// The fields of a layout resolved to the quantities a Scan needs.
struct CloudLayout {
  FieldSlot x, y, z, intensity, ring, time;
  double time_scale = 1.0;  ///< multiplies the raw time value to get seconds (1 or 1e-9)
  PointTimeReference time_reference = PointTimeReference::kRelative;
};

/// Resolves the fields of a cloud. Throws storey::Error (message without file
/// context) when x, y or z is missing, or a used field has an invalid datatype
/// or does not fit in `point_step`.
CloudLayout resolveCloudLayout(const std::vector<PointFieldDesc>& fields, std::uint32_t point_step);

struct PointFilter {
  double min_range = 0.3;    ///< [m]
  double max_range = 120.0;  ///< [m]
};

/// Points of one cloud with the count of each kind of point dropped.
struct DecodedCloud {
  std::vector<ScanPoint> points;  ///< kept points, in the order of the cloud
  std::int64_t non_finite = 0;    ///< x, y, z or time NaN / inf
  std::int64_t no_return = 0;     ///< x = y = z = 0 (organised clouds mark missing returns so)
  std::int64_t out_of_range = 0;  ///< range outside [min_range, max_range]
  std::int64_t invalid_ring = 0;  ///< ring value negative, above 65535 or not finite
};

/// Decodes every point of `cloud` (stamped `stamp_ns`) with `layout`. Ring
/// and time are 0 when the layout lacks them. Throws storey::Error (message
/// without file context) when the byte counts of the cloud are inconsistent.
DecodedCloud decodePointCloud(const PointCloudView& cloud, const CloudLayout& layout,
                              std::int64_t stamp_ns, const PointFilter& filter);

}  // namespace storey
