#pragma once
/// Absolute trajectory error: after aligning the estimate to the truth
/// (T_gt_est), the position error |p_gt - T_gt_est * p_est|, the rotation
/// error angle(R_gt^T R_gt_est R_est), and their parts that gravity sees at
/// every matched stamp: the height error |z_gt - z_est| and the tilt, the
/// angle between the true and the estimated up direction in the sensor frame
/// (R_gt^T z and R_est^T z; the error of roll and pitch, blind to yaw).
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/error_stats.h"

namespace storey::eval {

struct AteResult {
  Alignment alignment = Alignment::kNone;
  Pose T_gt_est;           ///< the alignment applied to the estimate
  ErrorStats translation;  ///< [m]
  ErrorStats rotation;     ///< [rad]
  ErrorStats vertical;     ///< |z_gt - z_est| [m]
  ErrorStats tilt;         ///< angle between the up directions [rad]
};

AteResult absoluteTrajectoryError(const AssociatedPoses& poses, Alignment alignment);

}  // namespace storey::eval
