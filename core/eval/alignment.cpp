#include "eval/alignment.h"

#include <Eigen/SVD>
#include <cmath>

#include "common/error.h"

namespace storey::eval {

const char* toString(Alignment alignment) {
  switch (alignment) {
    case Alignment::kNone:
      return "none";
    case Alignment::kSe3:
      return "se3";
    case Alignment::kYawTranslation:
      return "yaw_translation";
  }
  return "unknown";
}

namespace {

void checkPairs(const Positions& p_est, const Positions& p_gt) {
  if (p_est.size() != p_gt.size())
    throw Error("eval: alignment needs as many estimated as true positions");
  if (p_est.size() < 2) throw Error("eval: alignment needs at least 2 position pairs");
}

Eigen::Vector3d centroid(const Positions& p) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : p) sum += x;
  return sum / static_cast<double>(p.size());
}

}  // namespace

Pose alignSe3(const Positions& p_est, const Positions& p_gt) {
  checkPairs(p_est, p_gt);
  const Eigen::Vector3d c_est = centroid(p_est), c_gt = centroid(p_gt);
  // Cross-covariance H = sum (p_gt - c_gt)(p_est - c_est)^T; R = U S V^T with
  // S = diag(1, 1, det(U V^T)) so that R is a rotation, not a reflection.
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < p_est.size(); ++i)
    H += (p_gt[i] - c_gt) * (p_est[i] - c_est).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) S(2, 2) = -1.0;
  const Eigen::Matrix3d R_gt_est = svd.matrixU() * S * svd.matrixV().transpose();
  return Pose(R_gt_est, c_gt - R_gt_est * c_est);
}

Pose alignYawTranslation(const Positions& p_est, const Positions& p_gt) {
  checkPairs(p_est, p_gt);
  const Eigen::Vector3d c_est = centroid(p_est), c_gt = centroid(p_gt);
  // z is untouched by a rotation about z, so the yaw only has to fit the centred
  // xy coordinates: maximise sum cos(yaw) (a . b) + sin(yaw) (a x b)_z.
  double dot = 0.0, cross = 0.0;
  for (std::size_t i = 0; i < p_est.size(); ++i) {
    const Eigen::Vector3d a = p_est[i] - c_est, b = p_gt[i] - c_gt;
    dot += a.x() * b.x() + a.y() * b.y();
    cross += a.x() * b.y() - a.y() * b.x();
  }
  const double yaw = std::atan2(cross, dot);
  const Eigen::Matrix3d R_gt_est =
      Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return Pose(R_gt_est, c_gt - R_gt_est * c_est);
}

Pose align(Alignment alignment, const Positions& p_est, const Positions& p_gt) {
  switch (alignment) {
    case Alignment::kNone:
      return Pose::identity();
    case Alignment::kSe3:
      return alignSe3(p_est, p_gt);
    case Alignment::kYawTranslation:
      return alignYawTranslation(p_est, p_gt);
  }
  return Pose::identity();
}

}  // namespace storey::eval
