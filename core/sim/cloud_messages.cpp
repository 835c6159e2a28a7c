#include "sim/cloud_messages.h"

#include <cstring>

namespace storey::sim {

PointCloudMessage velodyneLayoutCloud(const Scan& scan) {
  constexpr std::uint32_t kStep = 32;
  PointCloudMessage msg;
  msg.stamp_ns = scan.stamp_ns;
  msg.frame_id = scan.frame_id;
  msg.height = 1;
  msg.width = static_cast<std::uint32_t>(scan.points.size());
  msg.fields = {{"x", 0, 7, 1},          {"y", 4, 7, 1},     {"z", 8, 7, 1},
                {"intensity", 16, 7, 1}, {"ring", 20, 4, 1}, {"time", 24, 7, 1}};
  msg.is_bigendian = false;
  msg.point_step = kStep;
  msg.row_step = kStep * msg.width;
  msg.is_dense = true;
  msg.data.assign(static_cast<std::size_t>(msg.row_step), 0);  // padding bytes are zero
  std::uint8_t* out = msg.data.data();
  for (const ScanPoint& p : scan.points) {
    std::memcpy(out + 0, &p.p.x(), 4);
    std::memcpy(out + 4, &p.p.y(), 4);
    std::memcpy(out + 8, &p.p.z(), 4);
    std::memcpy(out + 16, &p.intensity, 4);
    std::memcpy(out + 20, &p.ring, 2);
    std::memcpy(out + 24, &p.time, 4);
    out += kStep;
  }
  return msg;
}

PointCloudMessage ousterLayoutCloud(const OrganisedScan& scan, const std::string& frame_id,
                                    std::int64_t stamp_ns) {
  PointCloudMessage msg;
  msg.stamp_ns = stamp_ns;
  msg.frame_id = frame_id;
  msg.height = static_cast<std::uint32_t>(scan.rows);
  msg.width = static_cast<std::uint32_t>(scan.columns);
  for (const CloudField& f : kOusterFields) msg.fields.push_back({f.name, f.offset, f.datatype, 1});
  msg.is_bigendian = false;
  msg.point_step = kOusterPointStep;
  msg.row_step = kOusterPointStep * msg.width;
  msg.is_dense = true;
  msg.data.assign(static_cast<std::size_t>(msg.row_step) * msg.height, 0);
  std::uint8_t* out = msg.data.data();
  for (int row = 0; row < scan.rows; ++row) {
    const std::uint16_t ring = static_cast<std::uint16_t>(row);
    for (int column = 0; column < scan.columns; ++column) {
      const OrganisedPoint& p = scan.at(row, column);
      std::memcpy(out + 0, &p.p.x(), 4);
      std::memcpy(out + 4, &p.p.y(), 4);
      std::memcpy(out + 8, &p.p.z(), 4);
      std::memcpy(out + 16, &p.intensity, 4);
      std::memcpy(out + 20, &p.t_ns, 4);
      std::memcpy(out + 24, &p.reflectivity, 2);
      std::memcpy(out + 26, &ring, 2);
      std::memcpy(out + 32, &p.range_mm, 4);  // ambient (28) stays 0: no sunlight indoors
      out += kOusterPointStep;
    }
  }
  return msg;
}

}  // namespace storey::sim
