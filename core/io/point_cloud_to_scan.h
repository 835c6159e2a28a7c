#pragma once
/// Turns the clouds of one topic into Scans with rings numbered from the
/// lowest beam and per-point times relative to the header stamp, deriving
/// what a cloud lacks and warning once per topic about it.
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "io/point_cloud_decoder.h"
#include "io/point_cloud_layout.h"
#include "types/scan.h"
#include "types/sensor.h"

namespace storey {

/// Keys of LogReadStats::dropped for points (counts of points).
inline constexpr const char* kDropPointNotFinite = "point_not_finite";
inline constexpr const char* kDropPointNoReturn = "point_no_return";
inline constexpr const char* kDropPointOutOfRange = "point_out_of_range";
inline constexpr const char* kDropPointInvalidRing = "point_invalid_ring";

class PointCloudToScan {
 public:
  PointCloudToScan(std::string topic, LidarModel model, PointFilter filter);

  /// Decodes one cloud of the topic, in the order the clouds were recorded.
  /// Adds the counts of dropped points to `dropped`. Throws storey::Error
  /// (message without file context) for a cloud that cannot be decoded.
  Scan convert(const PointCloudView& cloud, std::int64_t stamp_ns, const std::string& frame_id,
               std::map<std::string, std::int64_t>& dropped);

  /// Current estimate of the time of one revolution [s] (median of recent stamp steps).
  double periodSeconds() const;

 private:
  const CloudLayout& layoutFor(const PointCloudView& cloud);
  void updatePeriod(std::int64_t stamp_ns);
  void renumberRings(std::vector<ScanPoint>& points, std::uint32_t height, std::int64_t& invalid);
  void deriveRings(std::vector<ScanPoint>& points);
  void warnOnce(const CloudLayout& layout);
  void checkTimeSpan(const std::vector<ScanPoint>& points);

  std::string topic_;
  LidarModel model_;
  PointFilter filter_;

  std::vector<PointFieldDesc> layout_fields_;  ///< fields the cached layout was resolved from
  std::uint32_t layout_point_step_ = 0;
  CloudLayout layout_;
  bool have_layout_ = false;

  std::int64_t previous_stamp_ns_ = 0;
  bool have_previous_stamp_ = false;
  std::deque<double> recent_steps_s_;  ///< last stamp steps, for the period estimate

  bool ring_order_decided_ = false;
  bool rings_top_down_ = false;
  std::uint16_t ring_count_ = 0;         ///< rings assumed when renumbering top-down rings
  std::vector<double> ring_elevations_;  ///< ascending [rad], for clouds without rings
  bool ring_elevations_final_ = false;

  bool warned_derived_ = false;
  bool warned_model_ = false;
  bool warned_time_span_ = false;
};

}  // namespace storey
