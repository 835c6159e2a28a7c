#include "eval/ate.h"

namespace storey::eval {

AteResult absoluteTrajectoryError(const AssociatedPoses& poses, Alignment alignment) {
  Positions p_est, p_gt;
  p_est.reserve(poses.matched());
  p_gt.reserve(poses.matched());
  for (std::size_t i = 0; i < poses.matched(); ++i) {
    p_est.push_back(poses.T_world_est[i].translation());
    p_gt.push_back(poses.T_world_gt[i].translation());
  }
  AteResult result;
  result.alignment = alignment;
  result.T_gt_est = align(alignment, p_est, p_gt);
  std::vector<double> translation, rotation;
  translation.reserve(poses.matched());
  rotation.reserve(poses.matched());
  for (std::size_t i = 0; i < poses.matched(); ++i) {
    const Pose T_world_est_aligned = result.T_gt_est * poses.T_world_est[i];
    translation.push_back(
        (poses.T_world_gt[i].translation() - T_world_est_aligned.translation()).norm());
    rotation.push_back((poses.T_world_gt[i].inverse() * T_world_est_aligned).angle());
  }
  result.translation = errorStats(std::move(translation));
  result.rotation = errorStats(std::move(rotation));
  return result;
}

}  // namespace storey::eval
