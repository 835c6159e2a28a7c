#pragma once
/// Relative pose error over path segments, as in the KITTI odometry benchmark:
/// for every start stamp i (every `stride`-th) the segment ends at the first
/// stamp j whose true path length from i reaches `segment_length`. The error of
/// the segment is E = (T_gt_i^-1 T_gt_j)^-1 (T_est_i^-1 T_est_j); its translation
/// |t_E| and angle(E) are divided by the segment's true path length (not the
/// nominal length, so a constant scale error s gives exactly |s - 1|).
/// Independent of any global alignment.
#include <vector>

#include "eval/association.h"
#include "eval/error_stats.h"

namespace storey::eval {

struct RpeResult {
  double segment_length = 10.0;    ///< nominal segment length [m]
  ErrorStats translation_percent;  ///< |t_E| / length * 100 [%]
  ErrorStats rotation_per_metre;   ///< angle(E) / length [rad/m]
};

/// No segment fits (the truth is shorter than segment_length): count 0, all zero.
/// Throws storey::Error for segment_length <= 0 or stride < 1.
RpeResult relativePoseError(const AssociatedPoses& poses, double segment_length, int stride = 1);

}  // namespace storey::eval
