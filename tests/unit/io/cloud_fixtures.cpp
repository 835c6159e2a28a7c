#include "unit/io/cloud_fixtures.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace storey::test {
namespace {

constexpr std::uint8_t kPadding = 0xEE;

template <typename T>
void put(std::vector<std::uint8_t>& bytes, std::size_t at, T value, bool big_endian = false) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian) std::reverse(raw, raw + sizeof(T));
  std::memcpy(bytes.data() + at, raw, sizeof(T));
}

PointFieldDesc field(const char* name, std::uint32_t offset, PointFieldType type) {
  return PointFieldDesc{name, offset, static_cast<std::uint8_t>(type), 1};
}

}  // namespace

PointCloudView TestCloud::view() const {
  PointCloudView v;
  v.fields = fields;
  v.height = height;
  v.width = width;
  v.point_step = point_step;
  v.row_step = row_step;
  v.is_bigendian = is_bigendian;
  v.data = data.data();
  v.size = data.size();
  return v;
}

CloudBuilder::CloudBuilder(std::vector<PointFieldDesc> fields, std::uint32_t point_step,
                           std::uint32_t width, std::uint32_t height, bool big_endian,
                           std::uint32_t row_padding) {
  cloud_.fields = std::move(fields);
  cloud_.point_step = point_step;
  cloud_.width = width;
  cloud_.height = height;
  cloud_.row_step = width * point_step + row_padding;
  cloud_.is_bigendian = big_endian;
  cloud_.data.assign(static_cast<std::size_t>(cloud_.row_step) * height, kPadding);
}

CloudBuilder& CloudBuilder::set(std::uint32_t index, const std::string& name, double value) {
  const auto f = std::find_if(cloud_.fields.begin(), cloud_.fields.end(),
                              [&](const PointFieldDesc& d) { return d.name == name; });
  if (f == cloud_.fields.end()) throw std::logic_error("test cloud has no field " + name);
  const std::size_t at = static_cast<std::size_t>(index / cloud_.width) * cloud_.row_step +
                         static_cast<std::size_t>(index % cloud_.width) * cloud_.point_step +
                         f->offset;
  const bool be = cloud_.is_bigendian;
  switch (static_cast<PointFieldType>(f->datatype)) {
    case PointFieldType::kInt8:
      put(cloud_.data, at, static_cast<std::int8_t>(value), be);
      break;
    case PointFieldType::kUint8:
      put(cloud_.data, at, static_cast<std::uint8_t>(value), be);
      break;
    case PointFieldType::kInt16:
      put(cloud_.data, at, static_cast<std::int16_t>(value), be);
      break;
    case PointFieldType::kUint16:
      put(cloud_.data, at, static_cast<std::uint16_t>(value), be);
      break;
    case PointFieldType::kInt32:
      put(cloud_.data, at, static_cast<std::int32_t>(value), be);
      break;
    case PointFieldType::kUint32:
      put(cloud_.data, at, static_cast<std::uint32_t>(value), be);
      break;
    case PointFieldType::kFloat32:
      put(cloud_.data, at, static_cast<float>(value), be);
      break;
    case PointFieldType::kFloat64:
      put(cloud_.data, at, value, be);
      break;
  }
  return *this;
}

TestCloud CloudBuilder::build(std::int64_t stamp_ns) const {
  TestCloud cloud = cloud_;
  cloud.stamp_ns = stamp_ns;
  return cloud;
}

TestCloud velodyneCloud(std::int64_t stamp_ns, const std::vector<VelodynePoint>& points) {
  TestCloud cloud;
  cloud.stamp_ns = stamp_ns;
  cloud.frame_id = "velodyne";
  cloud.fields = {
      field("x", 0, PointFieldType::kFloat32),    field("y", 4, PointFieldType::kFloat32),
      field("z", 8, PointFieldType::kFloat32),    field("intensity", 16, PointFieldType::kFloat32),
      field("ring", 20, PointFieldType::kUint16), field("time", 24, PointFieldType::kFloat32)};
  cloud.point_step = 32;
  cloud.width = static_cast<std::uint32_t>(points.size());
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.data.assign(cloud.row_step, kPadding);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t base = i * 32;
    put(cloud.data, base + 0, points[i].x);
    put(cloud.data, base + 4, points[i].y);
    put(cloud.data, base + 8, points[i].z);
    put(cloud.data, base + 16, points[i].intensity);
    put(cloud.data, base + 20, points[i].ring);
    put(cloud.data, base + 24, points[i].time);
  }
  return cloud;
}

TestCloud ousterCloud(std::int64_t stamp_ns, std::uint32_t width, std::uint32_t height,
                      const std::vector<OusterPoint>& points, OusterLayout layout) {
  if (points.size() != static_cast<std::size_t>(width) * height) {
    throw std::logic_error("ousterCloud: points must fill width x height");
  }
  std::vector<PointFieldDesc> fields;
  std::uint32_t step = 48;
  switch (layout) {
    case OusterLayout::kLegacyRingU8:
    case OusterLayout::kRingU16:
      fields = {field("x", 0, PointFieldType::kFloat32),
                field("y", 4, PointFieldType::kFloat32),
                field("z", 8, PointFieldType::kFloat32),
                field("intensity", 16, PointFieldType::kFloat32),
                field("t", 20, PointFieldType::kUint32),
                field("reflectivity", 24, PointFieldType::kUint16),
                field("ring", 26,
                      layout == OusterLayout::kLegacyRingU8 ? PointFieldType::kUint8
                                                            : PointFieldType::kUint16),
                field("ambient", 28, PointFieldType::kUint16),
                field("range", 32, PointFieldType::kUint32)};
      break;
    case OusterLayout::kLowDataIntensityU16:
      step = 20;
      fields = {field("x", 0, PointFieldType::kFloat32),
                field("y", 4, PointFieldType::kFloat32),
                field("z", 8, PointFieldType::kFloat32),
                field("t", 12, PointFieldType::kUint32),
                field("intensity", 16, PointFieldType::kUint16),
                field("ring", 18, PointFieldType::kUint16)};
      break;
  }
  CloudBuilder builder(fields, step, width, height);
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    builder.set(i, "x", p.x).set(i, "y", p.y).set(i, "z", p.z);
    builder.set(i, "intensity", p.intensity).set(i, "t", p.t).set(i, "ring", p.ring);
    if (layout != OusterLayout::kLowDataIntensityU16) {
      builder.set(i, "reflectivity", 7).set(i, "ambient", 9).set(i, "range", 1234);
    }
  }
  TestCloud cloud = builder.build(stamp_ns);
  cloud.frame_id = "os_sensor";
  return cloud;
}

TestCloud hesaiCloud(std::int64_t stamp_ns, const std::vector<HesaiPoint>& points) {
  CloudBuilder builder(
      {field("x", 0, PointFieldType::kFloat32), field("y", 4, PointFieldType::kFloat32),
       field("z", 8, PointFieldType::kFloat32), field("intensity", 16, PointFieldType::kFloat32),
       field("timestamp", 24, PointFieldType::kFloat64),
       field("ring", 32, PointFieldType::kUint16)},
      48, static_cast<std::uint32_t>(points.size()));
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    builder.set(i, "x", p.x).set(i, "y", p.y).set(i, "z", p.z).set(i, "intensity", p.intensity);
    builder.set(i, "timestamp", p.timestamp).set(i, "ring", p.ring);
  }
  TestCloud cloud = builder.build(stamp_ns);
  cloud.frame_id = "PandarXT-32";
  return cloud;
}

TestCloud xyzCloud(std::int64_t stamp_ns, const std::vector<std::vector<float>>& xyz) {
  CloudBuilder builder(
      {field("x", 0, PointFieldType::kFloat32), field("y", 4, PointFieldType::kFloat32),
       field("z", 8, PointFieldType::kFloat32)},
      12, static_cast<std::uint32_t>(xyz.size()));
  for (std::uint32_t i = 0; i < xyz.size(); ++i) {
    builder.set(i, "x", xyz[i].at(0)).set(i, "y", xyz[i].at(1)).set(i, "z", xyz[i].at(2));
  }
  return builder.build(stamp_ns);
}

}  // namespace storey::test
