#include "backend/solve_schedule.h"

#include <algorithm>
#include <cmath>

namespace storey::backend {

int wholeGraphInterval(const GraphConfig& config, int keyframes) {
  const int by_size = static_cast<int>(std::ceil(config.full_every_share * keyframes - 1e-9));
  return std::max({config.full_every, by_size, 1});
}

bool wholeGraphSolveDue(const GraphConfig& config, int since_whole, int keyframes) {
  if (config.window_keyframes <= 0 || since_whole < 0) return true;
  return since_whole >= wholeGraphInterval(config, keyframes);
}

}  // namespace storey::backend
