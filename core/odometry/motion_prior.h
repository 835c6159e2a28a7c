#pragma once
/// Prior on a motion block m = [v (3) [m/s], bias_gyro (3) [rad/s],
/// bias_accel (3) [m/s^2]] (imu/imu_state_blocks.h) together with the tilt of
/// gravity t = (t_x, t_y) [rad] (imu/imu_factor.h, ImuGravityFactor):
///   r = S ([m; t] - mean),  S^T S = Lambda (11x11 information matrix).
/// It carries what the window knew about the oldest state's velocity and
/// biases, and about gravity's direction, when older states left it (an
/// approximate marginalisation; see propagateMotionPrior), so the window's
/// oldest state is not frozen. The tilt and the accelerometer bias are
/// strongly correlated (one cannot be told from the other until the sensor
/// turns), so they share one prior.
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>

#include "imu/imu_factor.h"

namespace storey {

using Vector9d = Eigen::Matrix<double, 9, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector11d = Eigen::Matrix<double, 11, 1>;
using Matrix11d = Eigen::Matrix<double, 11, 11>;

struct MotionPrior {
  Vector11d mean = Vector11d::Zero();             ///< [v, bg, ba, tilt]
  Matrix11d information = Matrix11d::Identity();  ///< Lambda = covariance^-1
};

/// Blocks: motion (9), tilt (2).
class MotionPriorFactor final : public ceres::SizedCostFunction<11, 9, 2> {
 public:
  explicit MotionPriorFactor(const MotionPrior& prior);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Vector11d mean_;
  Eigen::Matrix<double, 11, 11, Eigen::RowMajor> sqrt_information_;
};

/// Diagonal prior from standard deviations of velocity, gyro and accel bias
/// and of the tilt of gravity.
MotionPrior diagonalMotionPrior(const Vector9d& motion, const Eigen::Vector2d& tilt,
                                double sigma_velocity, double sigma_gyro_bias,
                                double sigma_accel_bias, double sigma_tilt);

/// Information J^T J of the IMU factor i -> j (whitened) over the tangent
/// z = [pose_i (6), motion_i (9), pose_j (6), motion_j (9), tilt (2)], the
/// pose blocks' ambient Jacobians taken to the ImuPoseManifold's tangent.
Eigen::Matrix<double, 32, 32> imuFactorInformation(const ImuGravityFactor& factor,
                                                   const double* pose_i, const double* motion_i,
                                                   const double* pose_j, const double* motion_j,
                                                   const double* tilt);

/// The prior on [motion_j, tilt] when state i leaves the window.
/// Variables z = [pose_i (6, tangent), motion_i (9), pose_j (6), motion_j (9),
/// tilt (2)] with information from: the prior on [motion_i, tilt]; the IMU
/// factor i -> j (whitened Jacobian J, so J^T J); and a prior on each pose of
/// standard deviation pose_sigma_translation [m] / pose_sigma_rotation [rad],
/// the accuracy of LiDAR-registered poses (holding the poses exact would make
/// the velocity look known to 1e-4 m/s from the IMU's position delta).
/// Everything but [motion_j, tilt] is marginalised out (Schur complement),
/// linearised at the current estimates; the mean is their current estimate.
MotionPrior propagateMotionPrior(const MotionPrior& prior_i, const ImuGravityFactor& factor,
                                 const double* pose_i, const double* motion_i, const double* pose_j,
                                 const double* motion_j, const double* tilt,
                                 double pose_sigma_translation, double pose_sigma_rotation);

}  // namespace storey
