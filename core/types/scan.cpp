#include "types/scan.h"

#include <algorithm>

namespace storey {

std::pair<float, float> Scan::timeSpan() const {
  if (points.empty()) return {0.0f, 0.0f};
  auto [lo, hi] = std::minmax_element(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.time < b.time;
  });
  return {lo->time, hi->time};
}

}  // namespace storey
