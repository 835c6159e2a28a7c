#pragma once
/// The layout and bytes of a sensor_msgs/PointCloud2 message as plain types,
/// so that decoding needs no ROS headers (and can be tested without them).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace storey {

/// sensor_msgs/PointField datatype codes.
enum class PointFieldType : std::uint8_t {
  kInt8 = 1,
  kUint8 = 2,
  kInt16 = 3,
  kUint16 = 4,
  kInt32 = 5,
  kUint32 = 6,
  kFloat32 = 7,
  kFloat64 = 8,
};

/// One field descriptor of a cloud, as stored in the message.
struct PointFieldDesc {
  std::string name;
  std::uint32_t offset = 0;   ///< byte offset inside a point
  std::uint8_t datatype = 0;  ///< PointFieldType code (1..8); other values are invalid
  std::uint32_t count = 1;    ///< number of elements (only the first is read)
  bool operator==(const PointFieldDesc& o) const {
    return name == o.name && offset == o.offset && datatype == o.datatype && count == o.count;
  }
};

/// Size in bytes of one element of `datatype`; 0 for an invalid code.
std::size_t pointFieldTypeSize(std::uint8_t datatype);
/// "int8" .. "float64"; "invalid(N)" for an invalid code.
std::string pointFieldTypeName(std::uint8_t datatype);

/// A point cloud's layout and a view of its bytes (not owned). Points are
/// `height` rows of `width` points; row r starts at byte r * row_step and
/// point c of a row at c * point_step inside it.
struct PointCloudView {
  std::vector<PointFieldDesc> fields;
  std::uint32_t height = 1;
  std::uint32_t width = 0;
  std::uint32_t point_step = 0;  ///< bytes per point
  std::uint32_t row_step = 0;    ///< bytes per row
  bool is_bigendian = false;     ///< byte order of the fields in `data`
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;  ///< bytes available at `data`
};

}  // namespace storey
