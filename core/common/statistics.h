#pragma once
/// Order statistics of timing samples (the run report quotes median and p95).
#include <algorithm>
#include <cmath>
#include <vector>

namespace storey {

/// q-quantile (0..1) by the nearest-rank method; 0 for no samples.
inline double quantile(std::vector<double> samples, double q) {
  if (samples.empty()) return 0.0;
  const std::size_t rank = static_cast<std::size_t>(
      std::clamp(std::ceil(q * static_cast<double>(samples.size())) - 1.0, 0.0,
                 static_cast<double>(samples.size() - 1)));
  std::nth_element(samples.begin(), samples.begin() + rank, samples.end());
  return samples[rank];
}

inline double mean(const std::vector<double>& samples) {
  if (samples.empty()) return 0.0;
  double sum = 0.0;
  for (double s : samples) sum += s;
  return sum / static_cast<double>(samples.size());
}

}  // namespace storey
