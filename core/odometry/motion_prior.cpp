#include "odometry/motion_prior.h"

#include <Eigen/Cholesky>

#include "imu/imu_state_blocks.h"

namespace storey {

MotionPriorFactor::MotionPriorFactor(const MotionPrior& prior) : mean_(prior.mean) {
  // Lambda = L L^T, so S = L^T gives S^T S = Lambda.
  const Matrix9d information =
      0.5 * (prior.information + prior.information.transpose()) + 1e-9 * Matrix9d::Identity();
  sqrt_information_ = Eigen::LLT<Matrix9d>(information).matrixU();
}

bool MotionPriorFactor::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  const Eigen::Map<const Vector9d> m(parameters[0]);
  Eigen::Map<Vector9d> r(residuals);
  r = sqrt_information_ * (m - mean_);
  if (jacobians && jacobians[0]) {
    Eigen::Map<Eigen::Matrix<double, 9, 9, Eigen::RowMajor>> J(jacobians[0]);
    J = sqrt_information_;
  }
  return true;
}

MotionPrior diagonalMotionPrior(const Vector9d& mean, double sigma_velocity,
                                double sigma_gyro_bias, double sigma_accel_bias) {
  MotionPrior prior;
  prior.mean = mean;
  Vector9d inverse_variance;
  inverse_variance << Eigen::Vector3d::Constant(1.0 / (sigma_velocity * sigma_velocity)),
      Eigen::Vector3d::Constant(1.0 / (sigma_gyro_bias * sigma_gyro_bias)),
      Eigen::Vector3d::Constant(1.0 / (sigma_accel_bias * sigma_accel_bias));
  prior.information = inverse_variance.asDiagonal();
  return prior;
}

MotionPrior propagateMotionPrior(const MotionPrior& prior_i, const ImuFactor& factor,
                                 const double* pose_i, const double* motion_i,
                                 const double* pose_j, const double* motion_j,
                                 double pose_sigma_translation, double pose_sigma_rotation) {
  using RowMajor15x9 = Eigen::Matrix<double, 15, 9, Eigen::RowMajor>;
  using RowMajor15x7 = Eigen::Matrix<double, 15, 7, Eigen::RowMajor>;
  using RowMajor7x6 = Eigen::Matrix<double, 7, 6, Eigen::RowMajor>;
  RowMajor15x7 J_pose_i, J_pose_j;
  RowMajor15x9 J_motion_i, J_motion_j;
  double residual[15];
  const double* parameters[] = {pose_i, motion_i, pose_j, motion_j};
  double* jacobians[] = {J_pose_i.data(), J_motion_i.data(), J_pose_j.data(), J_motion_j.data()};
  factor.Evaluate(parameters, residual, jacobians);

  // Ambient (7) -> tangent (6) Jacobians of the pose blocks.
  const ImuPoseManifold manifold;
  RowMajor7x6 P_i, P_j;
  manifold.PlusJacobian(pose_i, P_i.data());
  manifold.PlusJacobian(pose_j, P_j.data());
  Eigen::Matrix<double, 15, 30> J;
  J << J_pose_i * P_i, J_motion_i, J_pose_j * P_j, J_motion_j;

  Eigen::Matrix<double, 30, 30> H = J.transpose() * J;
  H.block<9, 9>(6, 6) += prior_i.information;
  // The quaternion tangent delta rotates by 2 |delta|: sigma_delta = sigma_rotation / 2.
  Eigen::Matrix<double, 6, 1> pose_information;
  pose_information << Eigen::Vector3d::Constant(1.0 / (pose_sigma_translation * pose_sigma_translation)),
      Eigen::Vector3d::Constant(4.0 / (pose_sigma_rotation * pose_sigma_rotation));
  H.block<6, 6>(0, 0) += pose_information.asDiagonal();
  H.block<6, 6>(15, 15) += pose_information.asDiagonal();

  // Marginalise z_0..20 (pose_i, motion_i, pose_j) onto motion_j (z_21..29).
  const Eigen::Matrix<double, 21, 21> A = H.topLeftCorner<21, 21>();
  const Eigen::Matrix<double, 21, 9> B = H.topRightCorner<21, 9>();
  const Matrix9d C = H.bottomRightCorner<9, 9>();
  MotionPrior prior_j;
  prior_j.mean = Eigen::Map<const Vector9d>(motion_j);
  prior_j.information = C - B.transpose() * A.ldlt().solve(B);
  prior_j.information = 0.5 * (prior_j.information + prior_j.information.transpose());
  return prior_j;
}

}  // namespace storey
