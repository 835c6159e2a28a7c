#include "eval/error_stats.h"

#include <algorithm>
#include <cmath>

#include "common/statistics.h"

namespace storey::eval {

ErrorStats errorStats(std::vector<double> errors) {
  ErrorStats stats;
  stats.count = errors.size();
  if (errors.empty()) return stats;
  double sum = 0.0, sum_sq = 0.0;
  for (double e : errors) {
    sum += e;
    sum_sq += e * e;
    stats.max = std::max(stats.max, e);
  }
  const double n = static_cast<double>(errors.size());
  stats.mean = sum / n;
  stats.rmse = std::sqrt(sum_sq / n);
  stats.median = quantile(errors, 0.5);
  stats.p95 = quantile(std::move(errors), 0.95);
  return stats;
}

}  // namespace storey::eval
