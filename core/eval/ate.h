#pragma once
/// Absolute trajectory error: after aligning the estimate to the truth
/// (T_gt_est), the position error |p_gt - T_gt_est * p_est| and the rotation
/// error angle(R_gt^T R_gt_est R_est) at every matched stamp.
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/error_stats.h"

namespace storey::eval {

struct AteResult {
  Alignment alignment = Alignment::kNone;
  Pose T_gt_est;           ///< the alignment applied to the estimate
  ErrorStats translation;  ///< [m]
  ErrorStats rotation;     ///< [rad]
};

AteResult absoluteTrajectoryError(const AssociatedPoses& poses, Alignment alignment);

}  // namespace storey::eval
