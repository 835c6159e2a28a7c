#pragma once
/// Summary of a set of non-negative errors (ATE, RPE, map-to-mesh distances).
#include <cstddef>
#include <vector>

namespace storey::eval {

struct ErrorStats {
  std::size_t count = 0;
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double p95 = 0.0;  ///< 95th percentile (nearest rank)
  double max = 0.0;
};

/// Statistics of `errors` (all zero when empty). Takes the vector by value: it is reordered.
ErrorStats errorStats(std::vector<double> errors);

}  // namespace storey::eval
