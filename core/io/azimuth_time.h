#pragma once
/// Per-point times for clouds that carry none, from the azimuth of each point.
#include <vector>

#include "types/scan.h"

namespace storey {

/// Sets each point's time (relative to the header stamp, taken as the start of
/// the sweep) assuming a Velodyne-style spin: clockwise seen from above (z up),
/// one revolution in `period_s`, starting at the azimuth of the first point.
/// Times fall in [0, period_s).
void assignTimesFromAzimuth(std::vector<ScanPoint>& points, double period_s);

}  // namespace storey
