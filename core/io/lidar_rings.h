#pragma once
/// Ring numbers (laser index, 0 = lowest elevation) for clouds that do not
/// carry them, and a check of the numbering of clouds that do.
#include <cstdint>
#include <vector>

#include "types/scan.h"
#include "types/sensor.h"

namespace storey {

/// Elevation of a point seen from the LiDAR origin [rad], positive up.
double elevationOf(const ScanPoint& point);

/// Laser elevations of a known model, ascending [rad] (VLP-16: -15..+15 deg in
/// 2 deg steps; VLP-32C: -25..+15 deg, 32 lasers, the manual's uneven table;
/// HDL-32E: -30.67..+10.67 deg, 32 lasers; OS1-64: -16.6..+16.6 deg, 64
/// lasers evenly spaced). Empty for LidarModel::kGeneric.
std::vector<double> laserElevations(LidarModel model);

/// Index of the element of `ascending` nearest to `elevation` (ascending not empty).
std::uint16_t nearestRing(const std::vector<double>& ascending, double elevation);

/// Groups elevation angles [rad] into rings: sorted values are split where
/// consecutive ones differ by more than `min_gap`, and groups holding fewer
/// than 0.5 % of the values (stray returns between beams) are discarded.
/// Returns the groups' mean elevations, ascending; empty for no input.
std::vector<double> clusterElevations(std::vector<double> elevations, double min_gap);

/// Sets the ring of every point to its nearest entry of `ascending`.
void assignRingsByElevation(std::vector<ScanPoint>& points, const std::vector<double>& ascending);

/// Whether a cloud's ring numbers count from the top beam down (as Ouster's
/// driver numbers rows): compares the mean elevation of consecutive rings.
/// `decided` is false when fewer than two rings have points.
struct RingOrder {
  bool decided = false;
  bool top_down = false;       ///< ring 0 is the highest beam
  std::uint16_t max_ring = 0;  ///< largest ring number seen
};
RingOrder detectRingOrder(const std::vector<ScanPoint>& points);

}  // namespace storey
