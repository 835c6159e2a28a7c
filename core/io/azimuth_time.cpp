#include "io/azimuth_time.h"

#include <cmath>

namespace storey {

void assignTimesFromAzimuth(std::vector<ScanPoint>& points, double period_s) {
  if (points.empty()) return;
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  const double start = std::atan2(points.front().p.y(), points.front().p.x());
  for (auto& p : points) {
    // Clockwise seen from above: the azimuth (counter-clockwise positive) decreases.
    double swept = start - std::atan2(p.p.y(), p.p.x());
    swept -= kTwoPi * std::floor(swept / kTwoPi);  // into [0, 2 pi)
    if (swept >= kTwoPi) swept = 0.0;              // guards rounding at the upper end
    p.time = static_cast<float>(period_s * swept / kTwoPi);
  }
}

}  // namespace storey
