// Binary PLY and PCD exports of the map (fields: docs/outputs.md).
#include <ostream>

#include "common/atomic_file.h"
#include "export/binary_out.h"
#include "export/point_cloud_writers.h"
#include "export/point_selection.h"

namespace storey {

namespace {

using binary::putAt;
using binary::RecordBuffer;

/// The fields PLY and PCD records share, in their order (32 bytes): x y z
/// intensity (float), time (double), keyframe, storey (int32). Returns the
/// byte after them.
char* putSharedFields(char* b, const MapCloud& cloud, std::size_t i) {
  b = putAt<float>(b, cloud.positions[i].x());
  b = putAt<float>(b, cloud.positions[i].y());
  b = putAt<float>(b, cloud.positions[i].z());
  b = putAt<float>(b, cloud.intensity[i]);
  b = putAt<double>(b, cloud.time[i]);
  b = putAt<std::int32_t>(b, cloud.keyframe[i]);
  return putAt<std::int32_t>(b, cloud.storey[i]);
}

}  // namespace

void writePly(const std::string& path, const MapCloud& cloud,
              const std::vector<std::uint32_t>* indices) {
  const PointSelection selection(cloud.size(), indices);
  const std::size_t n = selection.size();
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "ply\n"
           "format binary_little_endian 1.0\n"
           "comment Storey map: world frame (z up, origin at the LiDAR's start), metres\n"
           "comment time: absolute time of the point [s]; storey: -1 = none; stairs: 0/1\n"
           "element vertex "
        << n
        << "\n"
           "property float x\n"
           "property float y\n"
           "property float z\n"
           "property float intensity\n"
           "property double time\n"
           "property int keyframe\n"
           "property int storey\n"
           "property uchar stairs\n"
           "end_header\n";
    RecordBuffer records(out, 33);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = selection.at(k);
      char* b = putSharedFields(records.next(), cloud, i);
      putAt<std::uint8_t>(b, (cloud.flags[i] & kMapPointStairs) ? 1 : 0);
    }
    records.flush();
  });
}

void writePcd(const std::string& path, const MapCloud& cloud,
              const std::vector<std::uint32_t>* indices) {
  const PointSelection selection(cloud.size(), indices);
  const std::size_t n = selection.size();
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "# .PCD v0.7 - Point Cloud Data file format (Storey map, world frame, metres)\n"
           "VERSION 0.7\n"
           "FIELDS x y z intensity time keyframe storey\n"
           "SIZE 4 4 4 4 8 4 4\n"
           "TYPE F F F F F I I\n"
           "COUNT 1 1 1 1 1 1 1\n"
           "WIDTH "
        << n << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA binary\n";
    RecordBuffer records(out, 32);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = selection.at(k);
      putSharedFields(records.next(), cloud, i);
    }
    records.flush();
  });
}

}  // namespace storey
