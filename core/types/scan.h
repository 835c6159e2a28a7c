#pragma once
/// One LiDAR revolution in the LiDAR frame. Per-point time is relative to the
/// scan's reference time (its header stamp), so that the points of a scan can
/// be deskewed to that time.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "common/time.h"

namespace storey {

struct ScanPoint {
  Eigen::Vector3f p = Eigen::Vector3f::Zero();  ///< position in the LiDAR frame [m]
  float intensity = 0.0f;                       ///< return intensity [sensor units]
  float time = 0.0f;     ///< firing time relative to Scan::stamp_ns [s]; may be negative
  std::uint16_t ring = 0;  ///< laser index, 0 = lowest elevation
};

struct Scan {
  std::int64_t stamp_ns = 0;      ///< reference time (header stamp) [ns]
  std::string frame_id;           ///< frame named by the source, informational
  std::vector<ScanPoint> points;  ///< in the LiDAR frame
  double time() const { return nsToSeconds(stamp_ns); }  ///< [s]
  /// [min, max] of point times relative to the stamp [s]; {0, 0} for an empty scan.
  std::pair<float, float> timeSpan() const;
};

}  // namespace storey
