#include "io/point_cloud_to_scan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/log.h"
#include "io/azimuth_time.h"
#include "io/lidar_rings.h"

namespace storey {
namespace {

constexpr double kDefaultPeriodS = 0.1;
constexpr std::size_t kPeriodSteps = 9;  ///< stamp steps in the median
constexpr double kClusterGapRad = 0.15 * 3.14159265358979323846 / 180.0;
constexpr std::size_t kPointsForFinalClusters = 1000;
constexpr double kMaxPlausibleTimeS = 1.0;  ///< |point time| beyond this is suspicious

std::string formatSeconds(double s) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", s);
  return text;
}

/// Median distance of the points' elevations to the nearest table entry, in
/// units of the table's mean spacing.
double tableMisfit(const std::vector<ScanPoint>& points, const std::vector<double>& table) {
  if (points.empty() || table.size() < 2) return 0.0;
  const double spacing = (table.back() - table.front()) / static_cast<double>(table.size() - 1);
  std::vector<double> misfit;
  misfit.reserve(points.size());
  for (const auto& p : points) {
    const double e = elevationOf(p);
    misfit.push_back(std::abs(e - table[nearestRing(table, e)]) / spacing);
  }
  std::nth_element(misfit.begin(), misfit.begin() + misfit.size() / 2, misfit.end());
  return misfit[misfit.size() / 2];
}

}  // namespace

PointCloudToScan::PointCloudToScan(std::string topic, LidarModel model, PointFilter filter)
    : topic_(std::move(topic)), model_(model), filter_(filter) {}

double PointCloudToScan::periodSeconds() const {
  if (recent_steps_s_.empty()) return kDefaultPeriodS;
  std::vector<double> steps(recent_steps_s_.begin(), recent_steps_s_.end());
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

Scan PointCloudToScan::convert(const PointCloudView& cloud, std::int64_t stamp_ns,
                               const std::string& frame_id,
                               std::map<std::string, std::int64_t>& dropped) {
  const CloudLayout& layout = layoutFor(cloud);
  updatePeriod(stamp_ns);
  DecodedCloud decoded = decodePointCloud(cloud, layout, stamp_ns, filter_);

  if (layout.ring.present) {
    renumberRings(decoded.points, cloud.height, decoded.invalid_ring);
  } else {
    deriveRings(decoded.points);
  }
  if (!layout.time.present) assignTimesFromAzimuth(decoded.points, periodSeconds());
  warnOnce(layout);
  checkTimeSpan(decoded.points);

  const auto count = [&dropped](const char* reason, std::int64_t n) {
    if (n > 0) dropped[reason] += n;
  };
  count(kDropPointNotFinite, decoded.non_finite);
  count(kDropPointNoReturn, decoded.no_return);
  count(kDropPointOutOfRange, decoded.out_of_range);
  count(kDropPointInvalidRing, decoded.invalid_ring);

  Scan scan;
  scan.stamp_ns = stamp_ns;
  scan.frame_id = frame_id;
  scan.points = std::move(decoded.points);
  return scan;
}

const CloudLayout& PointCloudToScan::layoutFor(const PointCloudView& cloud) {
  if (!have_layout_ || cloud.point_step != layout_point_step_ || cloud.fields != layout_fields_) {
    layout_ = resolveCloudLayout(cloud.fields, cloud.point_step);
    layout_fields_ = cloud.fields;
    layout_point_step_ = cloud.point_step;
    have_layout_ = true;
  }
  return layout_;
}

void PointCloudToScan::updatePeriod(std::int64_t stamp_ns) {
  if (have_previous_stamp_) {
    const double step = nsToSeconds(stamp_ns - previous_stamp_ns_);
    if (step > 0.0 && step <= 1.0) {
      recent_steps_s_.push_back(step);
      if (recent_steps_s_.size() > kPeriodSteps) recent_steps_s_.pop_front();
    }
  }
  previous_stamp_ns_ = stamp_ns;
  have_previous_stamp_ = true;
}

void PointCloudToScan::renumberRings(std::vector<ScanPoint>& points, std::uint32_t height,
                                     std::int64_t& invalid) {
  if (!ring_order_decided_) {
    const RingOrder order = detectRingOrder(points);
    if (!order.decided) return;
    ring_order_decided_ = true;
    rings_top_down_ = order.top_down;
    // An organised cloud has one row per beam; otherwise the model's laser
    // count, unless more rings were seen.
    const std::size_t seen = order.max_ring + 1u;
    const std::size_t rings =
        height > 1 && height >= seen ? height : std::max(seen, laserElevations(model_).size());
    ring_count_ = static_cast<std::uint16_t>(std::min<std::size_t>(rings, 65535));
    if (rings_top_down_) {
      logInfo(topic_ +
              ": the 'ring' field counts beams from the top; renumbered so that ring 0 "
              "is the lowest (" +
              std::to_string(ring_count_) + " rings)");
    }
  }
  if (!rings_top_down_) return;
  std::size_t kept = 0;
  for (auto& p : points) {
    if (p.ring >= ring_count_) {
      ++invalid;
      continue;
    }
    p.ring = static_cast<std::uint16_t>(ring_count_ - 1 - p.ring);
    points[kept++] = p;
  }
  points.resize(kept);
}

void PointCloudToScan::deriveRings(std::vector<ScanPoint>& points) {
  if (model_ != LidarModel::kGeneric) {
    if (ring_elevations_.empty()) ring_elevations_ = laserElevations(model_);
    if (!warned_model_ && !points.empty()) {
      warned_model_ = true;
      if (tableMisfit(points, ring_elevations_) > 0.25) {
        logWarning(topic_ + ": point elevations do not match the " + toString(model_) +
                   " laser table; rings may be wrong (check sensor.lidar_model; 'generic' "
                   "clusters the elevations instead)");
      }
    }
    assignRingsByElevation(points, ring_elevations_);
    return;
  }
  if (!ring_elevations_final_) {
    std::vector<double> elevations;
    elevations.reserve(points.size());
    for (const auto& p : points) elevations.push_back(elevationOf(p));
    std::vector<double> clusters = clusterElevations(std::move(elevations), kClusterGapRad);
    if (points.size() >= kPointsForFinalClusters || ring_elevations_.empty()) {
      ring_elevations_ = std::move(clusters);
    }
    if (points.size() >= kPointsForFinalClusters) {
      ring_elevations_final_ = true;
      logInfo(topic_ + ": " + std::to_string(ring_elevations_.size()) +
              " rings found by clustering point elevations");
    }
  }
  assignRingsByElevation(points, ring_elevations_);
}

void PointCloudToScan::warnOnce(const CloudLayout& layout) {
  if (warned_derived_ || (layout.ring.present && layout.time.present)) return;
  warned_derived_ = true;
  std::string message = topic_ + ":";
  if (!layout.ring.present) {
    message += std::string(" no 'ring' field, rings derived from elevation (") +
               (model_ == LidarModel::kGeneric ? "clustered elevations"
                                               : std::string(toString(model_)) + " laser table") +
               ")";
  }
  if (!layout.time.present) {
    if (!layout.ring.present) message += ";";
    message +=
        " no per-point time field, times derived from azimuth (clockwise spin over one "
        "scan period, estimated from the stamps; " +
        formatSeconds(kDefaultPeriodS) + " s until known)";
  }
  logWarning(message);
}

void PointCloudToScan::checkTimeSpan(const std::vector<ScanPoint>& points) {
  if (warned_time_span_ || points.empty()) return;
  const auto [lo, hi] = [&points] {
    float a = points.front().time, b = a;
    for (const auto& p : points) {
      a = std::min(a, p.time);
      b = std::max(b, p.time);
    }
    return std::make_pair(a, b);
  }();
  if (lo < -kMaxPlausibleTimeS || hi > kMaxPlausibleTimeS) {
    warned_time_span_ = true;
    logWarning(topic_ + ": point times span [" + formatSeconds(lo) + ", " + formatSeconds(hi) +
               "] s around the header stamp, more than a revolution: check the '" +
               layout_.time.name + "' field and the stamps");
  }
}

}  // namespace storey
