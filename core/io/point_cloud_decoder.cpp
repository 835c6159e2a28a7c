#include "io/point_cloud_decoder.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>

#include "common/error.h"
#include "common/time.h"

namespace storey {
namespace {

constexpr bool kHostBigEndian = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;

/// Above this many seconds a time value is taken as absolute (about 11.6 days
/// after the epoch: no scan lasts that long, every real clock is past it).
constexpr double kAbsoluteTimeThresholdS = 1e6;

template <typename T>
T load(const std::uint8_t* p, bool swap) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

double readNumber(const std::uint8_t* p, std::uint8_t datatype, bool swap) {
  switch (static_cast<PointFieldType>(datatype)) {
    case PointFieldType::kInt8:
      return load<std::int8_t>(p, swap);
    case PointFieldType::kUint8:
      return load<std::uint8_t>(p, swap);
    case PointFieldType::kInt16:
      return load<std::int16_t>(p, swap);
    case PointFieldType::kUint16:
      return load<std::uint16_t>(p, swap);
    case PointFieldType::kInt32:
      return load<std::int32_t>(p, swap);
    case PointFieldType::kUint32:
      return load<std::uint32_t>(p, swap);
    case PointFieldType::kFloat32:
      return load<float>(p, swap);
    case PointFieldType::kFloat64:
      return load<double>(p, swap);
  }
  return std::nan("");  // unreachable: datatypes are checked by resolveCloudLayout
}

bool isIntegerType(std::uint8_t datatype) {
  return datatype >= static_cast<std::uint8_t>(PointFieldType::kInt8) &&
         datatype <= static_cast<std::uint8_t>(PointFieldType::kUint32);
}

const PointFieldDesc* findField(const std::vector<PointFieldDesc>& fields,
                                std::initializer_list<const char*> names) {
  for (const char* name : names) {
    for (const auto& f : fields) {
      if (f.name == name) return &f;
    }
  }
  return nullptr;
}

FieldSlot makeSlot(const PointFieldDesc* field, std::uint32_t point_step) {
  FieldSlot slot;
  if (field == nullptr) return slot;
  const std::size_t size = pointFieldTypeSize(field->datatype);
  if (size == 0) {
    throw Error("field '" + field->name + "' has invalid datatype " +
                std::to_string(field->datatype) + " (expected 1..8)");
  }
  if (static_cast<std::uint64_t>(field->offset) + size > point_step) {
    throw Error("field '" + field->name + "' (" + pointFieldTypeName(field->datatype) +
                " at offset " + std::to_string(field->offset) + ") does not fit in point_step " +
                std::to_string(point_step));
  }
  slot.present = true;
  slot.name = field->name;
  slot.offset = field->offset;
  slot.datatype = field->datatype;
  return slot;
}

std::string fieldNames(const std::vector<PointFieldDesc>& fields) {
  if (fields.empty()) return "none";
  std::string names;
  for (const auto& f : fields) names += (names.empty() ? "" : ", ") + f.name;
  return names;
}

/// The time scale and reference of one cloud (resolves kDetect on its first finite value).
struct TimeConvention {
  double scale = 1.0;
  bool absolute = false;
};

TimeConvention timeConvention(const PointCloudView& cloud, const CloudLayout& layout, bool swap) {
  TimeConvention convention{layout.time_scale,
                            layout.time_reference == PointTimeReference::kAbsolute};
  if (layout.time_reference != PointTimeReference::kDetect) return convention;
  for (std::uint32_t row = 0; row < cloud.height; ++row) {
    for (std::uint32_t col = 0; col < cloud.width; ++col) {
      const std::uint8_t* point = cloud.data + static_cast<std::uint64_t>(row) * cloud.row_step +
                                  static_cast<std::uint64_t>(col) * cloud.point_step;
      const double raw = readNumber(point + layout.time.offset, layout.time.datatype, swap);
      if (!std::isfinite(raw)) continue;
      // Float values this large are nanoseconds (e.g. Livox); integers are ns already.
      if (convention.scale == 1.0 && std::abs(raw) > kAbsoluteTimeThresholdS * 1e9) {
        convention.scale = 1e-9;
      }
      convention.absolute = std::abs(raw * convention.scale) > kAbsoluteTimeThresholdS;
      return convention;
    }
  }
  return convention;
}

void checkSizes(const PointCloudView& cloud) {
  const std::uint64_t points = static_cast<std::uint64_t>(cloud.width) * cloud.height;
  if (points == 0) return;
  if (cloud.point_step == 0)
    throw Error("point_step is 0 in a cloud of " + std::to_string(points) + " points");
  const std::uint64_t row_bytes = static_cast<std::uint64_t>(cloud.width) * cloud.point_step;
  if (cloud.height > 1 && cloud.row_step < row_bytes) {
    throw Error("row_step " + std::to_string(cloud.row_step) + " is less than width " +
                std::to_string(cloud.width) + " x point_step " + std::to_string(cloud.point_step));
  }
  const std::uint64_t needed =
      static_cast<std::uint64_t>(cloud.height - 1) * cloud.row_step + row_bytes;
  if (cloud.data == nullptr || cloud.size < needed) {
    throw Error("data holds " + std::to_string(cloud.size) + " bytes but height " +
                std::to_string(cloud.height) + ", width " + std::to_string(cloud.width) +
                ", row_step " + std::to_string(cloud.row_step) + " and point_step " +
                std::to_string(cloud.point_step) + " need " + std::to_string(needed));
  }
}

}  // namespace

std::size_t pointFieldTypeSize(std::uint8_t datatype) {
  switch (datatype) {
    case 1:
    case 2:
      return 1;
    case 3:
    case 4:
      return 2;
    case 5:
    case 6:
    case 7:
      return 4;
    case 8:
      return 8;
    default:
      return 0;
  }
}

std::string pointFieldTypeName(std::uint8_t datatype) {
  static const char* const kNames[] = {"int8",  "uint8",  "int16",   "uint16",
                                       "int32", "uint32", "float32", "float64"};
  if (datatype >= 1 && datatype <= 8) return kNames[datatype - 1];
  return "invalid(" + std::to_string(datatype) + ")";
}

CloudLayout resolveCloudLayout(const std::vector<PointFieldDesc>& fields,
                               std::uint32_t point_step) {
  CloudLayout layout;
  for (const char* axis : {"x", "y", "z"}) {
    if (findField(fields, {axis}) == nullptr) {
      throw Error(std::string("point cloud has no '") + axis +
                  "' field (fields: " + fieldNames(fields) + ")");
    }
  }
  layout.x = makeSlot(findField(fields, {"x"}), point_step);
  layout.y = makeSlot(findField(fields, {"y"}), point_step);
  layout.z = makeSlot(findField(fields, {"z"}), point_step);
  layout.intensity = makeSlot(findField(fields, {"intensity", "reflectivity", "i"}), point_step);
  layout.ring = makeSlot(findField(fields, {"ring"}), point_step);

  const PointFieldDesc* time = findField(fields, {"time", "t", "offset_time", "timestamp"});
  layout.time = makeSlot(time, point_step);
  if (time != nullptr) {
    const bool integer = isIntegerType(time->datatype);
    layout.time_scale = integer ? 1e-9 : 1.0;
    layout.time_reference =
        time->name == "timestamp" ? PointTimeReference::kDetect : PointTimeReference::kRelative;
  }
  return layout;
}

DecodedCloud decodePointCloud(const PointCloudView& cloud, const CloudLayout& layout,
                              std::int64_t stamp_ns, const PointFilter& filter) {
  checkSizes(cloud);
  DecodedCloud out;
  const std::uint64_t count = static_cast<std::uint64_t>(cloud.width) * cloud.height;
  if (count == 0) return out;
  out.points.reserve(count);

  const bool swap = cloud.is_bigendian != kHostBigEndian;
  const TimeConvention time_convention =
      layout.time.present ? timeConvention(cloud, layout, swap) : TimeConvention{};
  const double stamp_s = nsToSeconds(stamp_ns);
  const double min_range2 = filter.min_range * filter.min_range;
  const double max_range2 = filter.max_range * filter.max_range;

  for (std::uint32_t row = 0; row < cloud.height; ++row) {
    const std::uint8_t* row_data = cloud.data + static_cast<std::uint64_t>(row) * cloud.row_step;
    for (std::uint32_t col = 0; col < cloud.width; ++col) {
      const std::uint8_t* point = row_data + static_cast<std::uint64_t>(col) * cloud.point_step;
      const double x = readNumber(point + layout.x.offset, layout.x.datatype, swap);
      const double y = readNumber(point + layout.y.offset, layout.y.datatype, swap);
      const double z = readNumber(point + layout.z.offset, layout.z.datatype, swap);
      double time = 0.0;
      if (layout.time.present) {
        const double raw = readNumber(point + layout.time.offset, layout.time.datatype, swap);
        time = time_convention.absolute ? raw * time_convention.scale - stamp_s
                                        : raw * time_convention.scale;
      }
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(time)) {
        ++out.non_finite;
        continue;
      }
      if (x == 0.0 && y == 0.0 && z == 0.0) {
        ++out.no_return;
        continue;
      }
      const double range2 = x * x + y * y + z * z;
      if (range2 < min_range2 || range2 > max_range2) {
        ++out.out_of_range;
        continue;
      }
      ScanPoint p;
      p.p = Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
      p.time = static_cast<float>(time);
      if (layout.intensity.present) {
        const double intensity =
            readNumber(point + layout.intensity.offset, layout.intensity.datatype, swap);
        p.intensity = std::isfinite(intensity) ? static_cast<float>(intensity) : 0.0f;
      }
      if (layout.ring.present) {
        const double ring = readNumber(point + layout.ring.offset, layout.ring.datatype, swap);
        if (!(ring >= 0.0 && ring <= 65535.0)) {
          ++out.invalid_ring;
          continue;
        }
        p.ring = static_cast<std::uint16_t>(ring);
      }
      out.points.push_back(p);
    }
  }
  return out;
}

}  // namespace storey
