#pragma once
/// Prior on a motion block m = [v (3) [m/s], bias_gyro (3) [rad/s],
/// bias_accel (3) [m/s^2]] (imu/imu_state_blocks.h):
///   r = S (m - m_prior),  S^T S = Lambda (information matrix).
/// It carries what the window knew about the oldest state's velocity and
/// biases when older states left it (an approximate marginalisation; see
/// propagateMotionPrior), so the window's oldest state is not frozen.
#include <Eigen/Core>
#include <ceres/sized_cost_function.h>

#include "imu/imu_factor.h"

namespace storey {

using Vector9d = Eigen::Matrix<double, 9, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;

struct MotionPrior {
  Vector9d mean = Vector9d::Zero();
  Matrix9d information = Matrix9d::Identity();  ///< Lambda = covariance^-1
};

class MotionPriorFactor final : public ceres::SizedCostFunction<9, 9> {
 public:
  explicit MotionPriorFactor(const MotionPrior& prior);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Vector9d mean_;
  Eigen::Matrix<double, 9, 9, Eigen::RowMajor> sqrt_information_;
};

/// Diagonal prior from standard deviations of velocity, gyro and accel bias.
MotionPrior diagonalMotionPrior(const Vector9d& mean, double sigma_velocity,
                                double sigma_gyro_bias, double sigma_accel_bias);

/// The prior on the motion of state j when state i leaves the window.
/// Variables z = [pose_i (6, tangent), motion_i (9), pose_j (6), motion_j (9)]
/// with information from: the prior on motion_i; the IMU factor i -> j
/// (whitened Jacobian J, so J^T J); and a prior on each pose of standard
/// deviation pose_sigma_translation [m] / pose_sigma_rotation [rad], the
/// accuracy of LiDAR-registered poses (holding the poses exact would make
/// the velocity look known to 1e-4 m/s from the IMU's position delta).
/// Everything but motion_j is marginalised out (Schur complement), linearised
/// at the current estimates; the mean is motion_j's current estimate.
MotionPrior propagateMotionPrior(const MotionPrior& prior_i, const ImuFactor& factor,
                                 const double* pose_i, const double* motion_i,
                                 const double* pose_j, const double* motion_j,
                                 double pose_sigma_translation, double pose_sigma_rotation);

}  // namespace storey
