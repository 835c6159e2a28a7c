#include "io/lidar_rings.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "io/velodyne/velodyne_tables.h"

namespace storey {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

std::vector<double> evenlySpacedDeg(double lowest_deg, double highest_deg, int lasers) {
  std::vector<double> table(lasers);
  for (int i = 0; i < lasers; ++i) {
    table[i] = (lowest_deg + (highest_deg - lowest_deg) * i / (lasers - 1)) * kDegToRad;
  }
  return table;
}

/// A Velodyne manual's table, ascending [rad].
std::vector<double> manualTable(velodyne::Model model) {
  std::vector<double> table;
  for (const velodyne::Laser& laser : velodyne::defaultCalibration(model).lasers)
    table.push_back(laser.elevation_deg * kDegToRad);
  std::sort(table.begin(), table.end());
  return table;
}

}  // namespace

double elevationOf(const ScanPoint& point) {
  const double x = point.p.x(), y = point.p.y(), z = point.p.z();
  return std::atan2(z, std::sqrt(x * x + y * y));
}

std::vector<double> laserElevations(LidarModel model) {
  switch (model) {
    case LidarModel::kVlp16:
      return evenlySpacedDeg(-15.0, 15.0, 16);
    case LidarModel::kVlp32c:
      return manualTable(velodyne::Model::kVlp32c);
    case LidarModel::kHdl32e:
      return evenlySpacedDeg(-92.0 / 3.0, 32.0 / 3.0, 32);
    case LidarModel::kOs1_64:
      return evenlySpacedDeg(-16.6, 16.6, 64);
    case LidarModel::kGeneric:
      return {};
  }
  return {};
}

std::uint16_t nearestRing(const std::vector<double>& ascending, double elevation) {
  const auto above = std::lower_bound(ascending.begin(), ascending.end(), elevation);
  if (above == ascending.begin()) return 0;
  if (above == ascending.end()) return static_cast<std::uint16_t>(ascending.size() - 1);
  const auto below = above - 1;
  const auto nearest = (elevation - *below <= *above - elevation) ? below : above;
  return static_cast<std::uint16_t>(nearest - ascending.begin());
}

std::vector<double> clusterElevations(std::vector<double> elevations, double min_gap) {
  std::vector<double> centres;
  if (elevations.empty()) return centres;
  std::sort(elevations.begin(), elevations.end());
  const std::size_t min_members =
      std::max<std::size_t>(1, static_cast<std::size_t>(0.005 * elevations.size()));
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= elevations.size(); ++i) {
    if (i < elevations.size() && elevations[i] - elevations[i - 1] <= min_gap) continue;
    if (i - begin >= min_members) {
      double sum = 0.0;
      for (std::size_t k = begin; k < i; ++k) sum += elevations[k];
      centres.push_back(sum / static_cast<double>(i - begin));
    }
    begin = i;
  }
  return centres;
}

void assignRingsByElevation(std::vector<ScanPoint>& points, const std::vector<double>& ascending) {
  if (ascending.empty()) return;
  for (auto& p : points) p.ring = nearestRing(ascending, elevationOf(p));
}

RingOrder detectRingOrder(const std::vector<ScanPoint>& points) {
  std::map<std::uint16_t, std::pair<double, int>> sum_by_ring;  // ring -> (sum, count)
  RingOrder order;
  for (const auto& p : points) {
    auto& entry = sum_by_ring[p.ring];
    entry.first += elevationOf(p);
    ++entry.second;
    order.max_ring = std::max(order.max_ring, p.ring);
  }
  if (sum_by_ring.size() < 2) return order;
  int rising = 0, falling = 0;
  double previous = 0.0;
  bool first = true;
  for (const auto& [ring, entry] : sum_by_ring) {
    const double mean = entry.first / entry.second;
    if (!first) (mean > previous ? rising : falling) += 1;
    previous = mean;
    first = false;
  }
  order.decided = true;
  order.top_down = falling > rising;
  return order;
}

}  // namespace storey
