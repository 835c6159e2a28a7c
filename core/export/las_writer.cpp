// LAS 1.4, point data record format 6 + extra bytes. Layout per the ASPRS
// LAS 1.4 R15 specification; fields used: docs/outputs.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <limits>
#include <ostream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/version.h"
#include "export/binary_out.h"
#include "export/point_cloud_writers.h"
#include "export/point_selection.h"

namespace storey {

namespace {

using binary::put;
using binary::putAt;
using binary::putChars;

/// One extra-bytes descriptor (192 bytes, LAS 1.4 R15 table 24).
void putExtraBytesDescriptor(std::string& out, std::uint8_t data_type, const std::string& name,
                             const std::string& description, bool has_no_data,
                             std::int64_t no_data) {
  put<std::uint16_t>(out, 0);                   // reserved
  put<std::uint8_t>(out, data_type);            // 3 = uint16, 4 = int16, 6 = int32, 1 = uint8
  put<std::uint8_t>(out, has_no_data ? 1 : 0);  // options: bit 0 no_data is valid
  putChars(out, name, 32);
  put<std::uint32_t>(out, 0);                         // unused
  put<std::int64_t>(out, has_no_data ? no_data : 0);  // no_data (anytype, 8 bytes)
  out.append(16, '\0');                               // deprecated1
  put<std::int64_t>(out, 0);                          // min
  out.append(16, '\0');                               // deprecated2
  put<std::int64_t>(out, 0);                          // max
  out.append(16, '\0');                               // deprecated3
  put<double>(out, 0.0);                              // scale (unused: options bit 3 clear)
  out.append(16, '\0');                               // deprecated4
  put<double>(out, 0.0);                              // offset (unused: options bit 4 clear)
  out.append(16, '\0');                               // deprecated5
  putChars(out, description, 32);
}

}  // namespace

void writeLas(const std::string& path, const MapCloud& cloud,
              const std::vector<std::uint32_t>* indices) {
  const PointSelection selection(cloud.size(), indices);
  const std::size_t n = selection.size();

  // Offsets: the minimum corner rounded down to the metre; bounds from the
  // quantised coordinates, so they agree exactly with the records.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  double earliest = 0.0;  // point time, for the header's creation day (below)
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d p = cloud.positions[selection.at(k)].cast<double>();
    if (!p.allFinite())
      throw Error(path + ": map point " + std::to_string(selection.at(k)) + " is not finite");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    const double t = cloud.time[selection.at(k)];
    if (k == 0 || t < earliest) earliest = t;
  }
  if (n == 0) lo = hi = Eigen::Vector3d::Zero();
  const Eigen::Vector3d offset(std::floor(lo.x()), std::floor(lo.y()), std::floor(lo.z()));
  auto quantise = [&](double v, int axis) -> std::int32_t {
    const double q = std::round((v - offset[axis]) / las::kScale);
    if (q > 2147483647.0 || q < -2147483648.0)
      throw Error(path + ": the map extends beyond what LAS can hold at 1 mm resolution");
    return static_cast<std::int32_t>(q);
  };
  std::array<std::int32_t, 3> qmin{0, 0, 0}, qmax{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    qmin[a] = quantise(lo[a], a);
    qmax[a] = quantise(hi[a], a);
  }

  std::string vlr;
  put<std::uint16_t>(vlr, 0);  // reserved
  putChars(vlr, "LASF_Spec", 16);
  put<std::uint16_t>(vlr, 4);  // record ID 4: extra bytes
  put<std::uint16_t>(vlr, 3 * 192);
  putChars(vlr, "Storey extra bytes", 32);
  putExtraBytesDescriptor(vlr, 4, "storey", "storey index, 0 = lowest", true, -1);
  putExtraBytesDescriptor(vlr, 6, "keyframe", "keyframe that observed the point", false, 0);
  putExtraBytesDescriptor(vlr, 1, "flags", "bit0 stairs, bit1 floor", false, 0);

  // The header's creation day is the day the data were recorded (UTC, from
  // the earliest point time: a log's clock is Unix time), so the same log
  // gives the same file on any day; a clock that is no date (before 1980,
  // e.g. time since the sensor booted) leaves the day and year 0.
  std::tm utc{};
  const bool dated = earliest >= 315532800.0 && earliest < 4102444800.0;  // 1980 .. 2100
  if (dated) {
    const std::time_t recorded = static_cast<std::time_t>(earliest);
    gmtime_r(&recorded, &utc);
  }

  std::string header;
  header.reserve(las::kHeaderSize);
  header += "LASF";
  put<std::uint16_t>(header, 0);  // file source ID
  // Global encoding: bit 4 (WKT) must be set with point formats 6-10; bit 0
  // clear: the time field is not adjusted GPS time (it is the log's clock).
  put<std::uint16_t>(header, 1u << 4);
  header.append(16, '\0');  // project GUID
  put<std::uint8_t>(header, 1);
  put<std::uint8_t>(header, 4);
  putChars(header, "Storey LiDAR-inertial SLAM", 32);
  putChars(header, std::string("Storey ") + storeyVersion(), 32);
  put<std::uint16_t>(header, static_cast<std::uint16_t>(dated ? utc.tm_yday + 1 : 0));
  put<std::uint16_t>(header, static_cast<std::uint16_t>(dated ? utc.tm_year + 1900 : 0));
  put<std::uint16_t>(header, las::kHeaderSize);
  put<std::uint32_t>(header, static_cast<std::uint32_t>(las::kHeaderSize + vlr.size()));
  put<std::uint32_t>(header, 1);  // number of VLRs
  put<std::uint8_t>(header, las::kPointFormat);
  put<std::uint16_t>(header, las::kRecordLength);
  // Legacy counts must be 0 with point formats 6-10 (no legacy compatibility).
  put<std::uint32_t>(header, 0);
  for (int r = 0; r < 5; ++r) put<std::uint32_t>(header, 0);
  for (int a = 0; a < 3; ++a) put<double>(header, las::kScale);
  for (int a = 0; a < 3; ++a) put<double>(header, offset[a]);
  for (int a = 0; a < 3; ++a) {
    put<double>(header, offset[a] + qmax[a] * las::kScale);
    put<double>(header, offset[a] + qmin[a] * las::kScale);
  }
  put<std::uint64_t>(header, 0);  // start of waveform data
  put<std::uint64_t>(header, 0);  // start of first EVLR
  put<std::uint32_t>(header, 0);  // number of EVLRs
  put<std::uint64_t>(header, n);  // number of point records
  put<std::uint64_t>(header, n);  // by return: every point is return 1 of 1
  for (int r = 1; r < 15; ++r) put<std::uint64_t>(header, 0);
  if (header.size() != las::kHeaderSize) throw Error("LAS header size mismatch (internal)");

  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(vlr.data(), static_cast<std::streamsize>(vlr.size()));
    binary::RecordBuffer records(out, las::kRecordLength);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = selection.at(k);
      const Eigen::Vector3d p = cloud.positions[i].cast<double>();
      char* b = records.next();
      b = putAt<std::int32_t>(b, quantise(p.x(), 0));
      b = putAt<std::int32_t>(b, quantise(p.y(), 1));
      b = putAt<std::int32_t>(b, quantise(p.z(), 2));
      const float intensity = std::clamp(cloud.intensity[i], 0.0f, 65535.0f);
      b = putAt<std::uint16_t>(b, static_cast<std::uint16_t>(std::lround(intensity)));
      b = putAt<std::uint8_t>(b, 0x11);  // return 1 of 1
      b = putAt<std::uint8_t>(b, 0);     // class flags, channel, scan direction, edge
      b = putAt<std::uint8_t>(b, 1);     // classification: unclassified
      const std::int16_t storey = cloud.storey[i];
      b = putAt<std::uint8_t>(
          b, storey >= 0 && storey < 255 ? static_cast<std::uint8_t>(storey) : std::uint8_t{255});
      b = putAt<std::int16_t>(b, 0);   // scan angle
      b = putAt<std::uint16_t>(b, 0);  // point source ID
      b = putAt<double>(b, cloud.time[i]);
      b = putAt<std::int16_t>(b, storey);
      b = putAt<std::int32_t>(b, cloud.keyframe[i]);
      putAt<std::uint8_t>(b, cloud.flags[i]);
    }
    records.flush();
  });
}

}  // namespace storey
