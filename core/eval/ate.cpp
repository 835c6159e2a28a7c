#include "eval/ate.h"

#include <cmath>

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
  std::vector<double> translation, rotation, vertical, tilt;
  translation.reserve(poses.matched());
  rotation.reserve(poses.matched());
  vertical.reserve(poses.matched());
  tilt.reserve(poses.matched());
  for (std::size_t i = 0; i < poses.matched(); ++i) {
    const Pose T_world_est_aligned = result.T_gt_est * poses.T_world_est[i];
    translation.push_back(
        (poses.T_world_gt[i].translation() - T_world_est_aligned.translation()).norm());
    rotation.push_back((poses.T_world_gt[i].inverse() * T_world_est_aligned).angle());
    vertical.push_back(
        std::abs(poses.T_world_gt[i].translation().z() - T_world_est_aligned.translation().z()));
    const Eigen::Vector3d up_gt =
        poses.T_world_gt[i].rotation().conjugate() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d up_est =
        T_world_est_aligned.rotation().conjugate() * Eigen::Vector3d::UnitZ();
    // atan2 of |cross| and dot: accurate for small angles, where acos is not.
    tilt.push_back(std::atan2(up_gt.cross(up_est).norm(), up_gt.dot(up_est)));
  }
  result.translation = errorStats(std::move(translation));
  result.rotation = errorStats(std::move(rotation));
  result.vertical = errorStats(std::move(vertical));
  result.tilt = errorStats(std::move(tilt));
  return result;
}

}  // namespace storey::eval
