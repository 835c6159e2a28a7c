#pragma once
/// Closed-form alignment of estimated positions to true ones, no scale:
/// T_gt_est minimises sum_i |p_gt_i - T_gt_est * p_est_i|^2.
#include <string>
#include <vector>

#include "types/pose.h"

namespace storey::eval {

enum class Alignment {
  kNone,            ///< both already in the same world frame (gravity-aligned, origin at the start)
  kSe3,             ///< rotation + translation (Umeyama / Horn, no scale)
  kYawTranslation,  ///< rotation about z + translation (4 DoF; gravity-aligned estimates)
};
const char* toString(Alignment alignment);  ///< "none", "se3", "yaw_translation"

using Positions = std::vector<Eigen::Vector3d>;

/// Umeyama's closed form (SVD of the cross-covariance, reflection excluded).
/// Throws storey::Error for fewer than 2 pairs or different sizes.
Pose alignSe3(const Positions& p_est, const Positions& p_gt);
/// Rotation about z (closed form on the centred xy coordinates) and translation.
Pose alignYawTranslation(const Positions& p_est, const Positions& p_gt);
/// Dispatches on `alignment` (kNone gives the identity).
Pose align(Alignment alignment, const Positions& p_est, const Positions& p_gt);

}  // namespace storey::eval
