#pragma once
/// The run's own plane-fit noise, for the rough-fit gate of the association
/// (docs/method/backend.md, "Rough fits are not used"): the median fit RMS of
/// every SRP extracted so far. An SRP whose RMS exceeds `max_ratio` times that
/// median is mostly a band of several surfaces (treads and risers near the
/// sensor in a stairwell, a slab edge), not one plane: its fit is biased by
/// centimetres and its covariance does not show it. The scale comes from the
/// run, so the gate decides alike for a 1 cm and a 2 cm sensor; it cannot
/// fire once the planes' own RMS nears the band's ceiling (inliers within
/// +-ransac_distance: about 0.029 m at the default 0.05 m).
#include <cstdint>
#include <functional>
#include <queue>
#include <vector>

namespace storey::backend {

class FitNoise {
 public:
  /// `max_ratio` 0 switches the gate off; it acts once `min_samples` RMS
  /// values have been added.
  FitNoise(double max_ratio, int min_samples);

  /// True when an SRP of fit RMS `rms` [m] is too rough to use, judged on the
  /// SRPs added so far.
  bool rough(double rms) const;
  /// Adds one SRP's fit RMS [m] (every SRP, rough or not).
  void add(double rms);

  /// Median of the RMS values added (the lower middle one of an even count);
  /// 0 before any [m].
  double median() const { return lower_.empty() ? 0.0 : lower_.top(); }
  std::int64_t samples() const { return samples_; }

 private:
  double max_ratio_;
  int min_samples_;
  std::int64_t samples_ = 0;
  // The lower half (max at the top) and the upper half (min at the top);
  // lower_ holds the middle element of an odd count.
  std::priority_queue<double> lower_;
  std::priority_queue<double, std::vector<double>, std::greater<double>> upper_;
};

}  // namespace storey::backend
