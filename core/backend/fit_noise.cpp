#include "backend/fit_noise.h"

namespace storey::backend {

FitNoise::FitNoise(double max_ratio, int min_samples)
    : max_ratio_(max_ratio), min_samples_(min_samples) {}

bool FitNoise::rough(double rms) const {
  return max_ratio_ > 0 && samples_ >= min_samples_ && rms > max_ratio_ * median();
}

void FitNoise::add(double rms) {
  ++samples_;
  if (lower_.empty() || rms <= lower_.top())
    lower_.push(rms);
  else
    upper_.push(rms);
  // Rebalance: |lower| = |upper| or |upper| + 1.
  if (lower_.size() > upper_.size() + 1) {
    upper_.push(lower_.top());
    lower_.pop();
  } else if (upper_.size() > lower_.size()) {
    lower_.push(upper_.top());
    upper_.pop();
  }
}

}  // namespace storey::backend
