#pragma once
/// Prior on a motion block [v (3) [m/s], bias_gyro (3) [rad/s], bias_accel (3)
/// [m/s^2]] (imu/imu_state_blocks.h): r = diag(1 / sigma) (m - m_prior).
/// Holds the window's oldest velocity and biases near their last estimate
/// without freezing them (the oldest pose is the window's fixed anchor).
#include <Eigen/Core>
#include <ceres/sized_cost_function.h>

namespace storey {

class MotionPriorFactor final : public ceres::SizedCostFunction<9, 9> {
 public:
  MotionPriorFactor(const Eigen::Matrix<double, 9, 1>& prior, const Eigen::Matrix<double, 9, 1>& sigma)
      : prior_(prior), inverse_sigma_(sigma.cwiseInverse()) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Matrix<double, 9, 1>> m(parameters[0]);
    Eigen::Map<Eigen::Matrix<double, 9, 1>> r(residuals);
    r = inverse_sigma_.cwiseProduct(m - prior_);
    if (jacobians && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 9, 9, Eigen::RowMajor>> J(jacobians[0]);
      J = inverse_sigma_.asDiagonal();
    }
    return true;
  }

 private:
  Eigen::Matrix<double, 9, 1> prior_;
  Eigen::Matrix<double, 9, 1> inverse_sigma_;
};

}  // namespace storey
