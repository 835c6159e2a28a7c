#include "odometry/motion_prior.h"

#include <Eigen/Cholesky>

#include "imu/imu_state_blocks.h"

namespace storey {

MotionPriorFactor::MotionPriorFactor(const MotionPrior& prior) : mean_(prior.mean) {
  // Lambda = L L^T, so S = L^T gives S^T S = Lambda.
  const Matrix11d information =
      0.5 * (prior.information + prior.information.transpose()) + 1e-9 * Matrix11d::Identity();
  sqrt_information_ = Eigen::LLT<Matrix11d>(information).matrixU();
}

bool MotionPriorFactor::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  Vector11d x;
  x.head<9>() = Eigen::Map<const Vector9d>(parameters[0]);
  x.tail<2>() = Eigen::Map<const Eigen::Vector2d>(parameters[1]);
  Eigen::Map<Vector11d> r(residuals);
  r = sqrt_information_ * (x - mean_);
  if (jacobians && jacobians[0]) {
    Eigen::Map<Eigen::Matrix<double, 11, 9, Eigen::RowMajor>> J(jacobians[0]);
    J = sqrt_information_.leftCols<9>();
  }
  if (jacobians && jacobians[1]) {
    Eigen::Map<Eigen::Matrix<double, 11, 2, Eigen::RowMajor>> J(jacobians[1]);
    J = sqrt_information_.rightCols<2>();
  }
  return true;
}

MotionPrior diagonalMotionPrior(const Vector9d& motion, const Eigen::Vector2d& tilt,
                                double sigma_velocity, double sigma_gyro_bias,
                                double sigma_accel_bias, double sigma_tilt) {
  MotionPrior prior;
  prior.mean << motion, tilt;
  Vector11d inverse_variance;
  inverse_variance << Eigen::Vector3d::Constant(1.0 / (sigma_velocity * sigma_velocity)),
      Eigen::Vector3d::Constant(1.0 / (sigma_gyro_bias * sigma_gyro_bias)),
      Eigen::Vector3d::Constant(1.0 / (sigma_accel_bias * sigma_accel_bias)),
      Eigen::Vector2d::Constant(1.0 / (sigma_tilt * sigma_tilt));
  prior.information = inverse_variance.asDiagonal();
  return prior;
}

Eigen::Matrix<double, 32, 32> imuFactorInformation(const ImuGravityFactor& factor,
                                                   const double* pose_i, const double* motion_i,
                                                   const double* pose_j, const double* motion_j,
                                                   const double* tilt) {
  using RowMajor15x9 = Eigen::Matrix<double, 15, 9, Eigen::RowMajor>;
  using RowMajor15x7 = Eigen::Matrix<double, 15, 7, Eigen::RowMajor>;
  using RowMajor15x2 = Eigen::Matrix<double, 15, 2, Eigen::RowMajor>;
  using RowMajor7x6 = Eigen::Matrix<double, 7, 6, Eigen::RowMajor>;
  RowMajor15x7 J_pose_i, J_pose_j;
  RowMajor15x9 J_motion_i, J_motion_j;
  RowMajor15x2 J_tilt;
  double residual[15];
  const double* parameters[] = {pose_i, motion_i, pose_j, motion_j, tilt};
  double* jacobians[] = {J_pose_i.data(), J_motion_i.data(), J_pose_j.data(), J_motion_j.data(),
                         J_tilt.data()};
  factor.Evaluate(parameters, residual, jacobians);

  // Ambient (7) -> tangent (6) Jacobians of the pose blocks.
  const ImuPoseManifold manifold;
  RowMajor7x6 P_i, P_j;
  manifold.PlusJacobian(pose_i, P_i.data());
  manifold.PlusJacobian(pose_j, P_j.data());
  // z = [pose_i 0..5, motion_i 6..14, pose_j 15..20, motion_j 21..29, tilt 30..31]
  Eigen::Matrix<double, 15, 32> J;
  J << J_pose_i * P_i, J_motion_i, J_pose_j * P_j, J_motion_j, J_tilt;

  return J.transpose() * J;
}

MotionPrior propagateMotionPrior(const MotionPrior& prior_i, const ImuGravityFactor& factor,
                                 const double* pose_i, const double* motion_i, const double* pose_j,
                                 const double* motion_j, const double* tilt,
                                 double pose_sigma_translation, double pose_sigma_rotation) {
  Eigen::Matrix<double, 32, 32> H =
      imuFactorInformation(factor, pose_i, motion_i, pose_j, motion_j, tilt);
  H.block<9, 9>(6, 6) += prior_i.information.topLeftCorner<9, 9>();
  H.block<9, 2>(6, 30) += prior_i.information.topRightCorner<9, 2>();
  H.block<2, 9>(30, 6) += prior_i.information.bottomLeftCorner<2, 9>();
  H.block<2, 2>(30, 30) += prior_i.information.bottomRightCorner<2, 2>();
  // The quaternion tangent delta rotates by 2 |delta|: sigma_delta = sigma_rotation / 2.
  Eigen::Matrix<double, 6, 1> pose_information;
  pose_information << Eigen::Vector3d::Constant(1.0 /
                                                (pose_sigma_translation * pose_sigma_translation)),
      Eigen::Vector3d::Constant(4.0 / (pose_sigma_rotation * pose_sigma_rotation));
  H.block<6, 6>(0, 0) += pose_information.asDiagonal();
  H.block<6, 6>(15, 15) += pose_information.asDiagonal();

  // Marginalise z_0..20 (pose_i, motion_i, pose_j) onto [motion_j, tilt] (z_21..31).
  const Eigen::Matrix<double, 21, 21> A = H.topLeftCorner<21, 21>();
  const Eigen::Matrix<double, 21, 11> B = H.topRightCorner<21, 11>();
  const Matrix11d C = H.bottomRightCorner<11, 11>();
  MotionPrior prior_j;
  prior_j.mean << Eigen::Map<const Vector9d>(motion_j), Eigen::Map<const Eigen::Vector2d>(tilt);
  prior_j.information = C - B.transpose() * A.ldlt().solve(B);
  prior_j.information = 0.5 * (prior_j.information + prior_j.information.transpose());
  return prior_j;
}

}  // namespace storey
