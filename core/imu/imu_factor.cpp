#include "imu/imu_factor.h"

#include <Eigen/Cholesky>

#include "common/error.h"
#include "imu/imu_state_blocks.h"
#include "imu/so3.h"

namespace storey {
namespace {

/// Added to the covariance's diagonal so that a zero random walk (bias held
/// fixed) still gives a positive-definite matrix: 1e-18 is a std of 1e-9.
constexpr double kVarianceFloor = 1e-18;

using Matrix15x6 = Eigen::Matrix<double, 15, 6>;
using Matrix15x9 = Eigen::Matrix<double, 15, 9>;

/// 2 * PlusJacobian(q)^T of EigenQuaternionManifold (q = [x y z w]): maps a
/// Jacobian w.r.t. a left rotation vector a to the ambient quaternion
/// coefficients (see the header).
Eigen::Matrix<double, 3, 4> liftToQuaternion(const Eigen::Quaterniond& q) {
  Eigen::Matrix<double, 4, 3> P;
  P.topRows<3>() = q.w() * Eigen::Matrix3d::Identity() - so3::skew(q.vec());
  P.bottomRows<1>() = -q.vec().transpose();
  return 2.0 * P.transpose();
}

}  // namespace

ImuFactor::ImuFactor(const ImuPreintegration& preintegration)
    : dR_(preintegration.deltas().dR),
      dv_(preintegration.deltas().dv),
      dp_(preintegration.deltas().dp),
      dR_dbg_(preintegration.dR_dbg()),
      dv_dbg_(preintegration.dv_dbg()),
      dv_dba_(preintegration.dv_dba()),
      dp_dbg_(preintegration.dp_dbg()),
      dp_dba_(preintegration.dp_dba()),
      bias_lin_(preintegration.biasLinearisation()),
      gravity_(preintegration.gravity()),
      dt_(preintegration.duration()) {
  Matrix15d covariance = preintegration.covariance();
  covariance.diagonal().array() += kVarianceFloor;
  const Eigen::LLT<Matrix15d> llt(covariance);
  if (llt.info() != Eigen::Success) {
    throw Error(
        "IMU factor: the preintegrated covariance is not positive definite "
        "(check the IMU noise densities)");
  }
  sqrt_information_ = llt.matrixL().solve(Matrix15d::Identity());
}

bool ImuFactor::Evaluate(double const* const* parameters, double* residuals,
                         double** jacobians) const {
  return evaluateWithGravity(parameters, gravity_, residuals, jacobians, nullptr);
}

bool ImuFactor::evaluateWithGravity(double const* const* parameters,
                                    const Eigen::Vector3d& gravity_world, double* residuals,
                                    double** jacobians, double* jacobian_gravity) const {
  const Eigen::Map<const Eigen::Vector3d> p_i(parameters[0]);
  const Eigen::Quaterniond q_i =
      Eigen::Map<const Eigen::Quaterniond>(parameters[0] + 3).normalized();
  const Eigen::Map<const Eigen::Vector3d> v_i(parameters[1]);
  const Eigen::Map<const Eigen::Vector3d> bg_i(parameters[1] + 3);
  const Eigen::Map<const Eigen::Vector3d> ba_i(parameters[1] + 6);
  const Eigen::Map<const Eigen::Vector3d> p_j(parameters[2]);
  const Eigen::Quaterniond q_j =
      Eigen::Map<const Eigen::Quaterniond>(parameters[2] + 3).normalized();
  const Eigen::Map<const Eigen::Vector3d> v_j(parameters[3]);
  const Eigen::Map<const Eigen::Vector3d> bg_j(parameters[3] + 3);
  const Eigen::Map<const Eigen::Vector3d> ba_j(parameters[3] + 6);

  const Eigen::Vector3d dbg = bg_i - bias_lin_.gyro;
  const Eigen::Vector3d dba = ba_i - bias_lin_.accel;
  const Eigen::Vector3d phi_corr = dR_dbg_ * dbg;
  const Eigen::Quaterniond dR_corr = dR_ * so3::expQuaternion(phi_corr);
  const Eigen::Matrix3d Ri_T = q_i.toRotationMatrix().transpose();
  const Eigen::Vector3d w_v = v_j - v_i - gravity_world * dt_;
  const Eigen::Vector3d w_p = p_j - p_i - v_i * dt_ - 0.5 * dt_ * dt_ * gravity_world;
  const Eigen::Quaterniond q_err = dR_corr.conjugate() * q_i.conjugate() * q_j;

  Eigen::Matrix<double, 15, 1> r;
  r.segment<3>(0) = so3::logQuaternion(q_err);
  r.segment<3>(3) = Ri_T * w_v - (dv_ + dv_dbg_ * dbg + dv_dba_ * dba);
  r.segment<3>(6) = Ri_T * w_p - (dp_ + dp_dbg_ * dbg + dp_dba_ * dba);
  r.segment<3>(9) = bg_j - bg_i;
  r.segment<3>(12) = ba_j - ba_i;
  const auto L_inv = sqrt_information_.triangularView<Eigen::Lower>();
  Eigen::Map<Eigen::Matrix<double, 15, 1>> r_out(residuals);
  r_out = L_inv * r;
  if (jacobian_gravity != nullptr) {
    Eigen::Matrix<double, 15, 3> J = Eigen::Matrix<double, 15, 3>::Zero();
    J.block<3, 3>(3, 0) = -Ri_T * dt_;
    J.block<3, 3>(6, 0) = -0.5 * dt_ * dt_ * Ri_T;
    Eigen::Map<Eigen::Matrix<double, 15, 3, Eigen::RowMajor>> out(jacobian_gravity);
    out = L_inv * J;
  }
  if (jacobians == nullptr) return true;

  const Eigen::Vector3d r_R = r.segment<3>(0);
  const Eigen::Matrix3d Jr_inv = so3::rightJacobianInverse(r_R);
  const Eigen::Matrix3d Rj_T = q_j.toRotationMatrix().transpose();
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();

  if (jacobians[0] != nullptr) {  // pose_i: tangent [dp, a]
    Matrix15x6 J = Matrix15x6::Zero();
    J.block<3, 3>(0, 3) = -Jr_inv * Rj_T;
    J.block<3, 3>(3, 3) = Ri_T * so3::skew(w_v);
    J.block<3, 3>(6, 0) = -Ri_T;
    J.block<3, 3>(6, 3) = Ri_T * so3::skew(w_p);
    const Matrix15x6 Jw = L_inv * J;
    Eigen::Map<Eigen::Matrix<double, 15, 7, Eigen::RowMajor>> out(jacobians[0]);
    out.leftCols<3>() = Jw.leftCols<3>();
    out.rightCols<4>() = Jw.rightCols<3>() * liftToQuaternion(q_i);
  }
  if (jacobians[1] != nullptr) {  // motion_i: [v, bg, ba]
    Matrix15x9 J = Matrix15x9::Zero();
    J.block<3, 3>(0, 3) =
        -Jr_inv * so3::expMatrix(r_R).transpose() * so3::rightJacobian(phi_corr) * dR_dbg_;
    J.block<3, 3>(3, 0) = -Ri_T;
    J.block<3, 3>(3, 3) = -dv_dbg_;
    J.block<3, 3>(3, 6) = -dv_dba_;
    J.block<3, 3>(6, 0) = -Ri_T * dt_;
    J.block<3, 3>(6, 3) = -dp_dbg_;
    J.block<3, 3>(6, 6) = -dp_dba_;
    J.block<3, 3>(9, 3) = -I3;
    J.block<3, 3>(12, 6) = -I3;
    Eigen::Map<Eigen::Matrix<double, 15, 9, Eigen::RowMajor>> out(jacobians[1]);
    out = L_inv * J;
  }
  if (jacobians[2] != nullptr) {  // pose_j
    Matrix15x6 J = Matrix15x6::Zero();
    J.block<3, 3>(0, 3) = Jr_inv * Rj_T;
    J.block<3, 3>(6, 0) = Ri_T;
    const Matrix15x6 Jw = L_inv * J;
    Eigen::Map<Eigen::Matrix<double, 15, 7, Eigen::RowMajor>> out(jacobians[2]);
    out.leftCols<3>() = Jw.leftCols<3>();
    out.rightCols<4>() = Jw.rightCols<3>() * liftToQuaternion(q_j);
  }
  if (jacobians[3] != nullptr) {  // motion_j
    Matrix15x9 J = Matrix15x9::Zero();
    J.block<3, 3>(3, 0) = Ri_T;
    J.block<3, 3>(9, 3) = I3;
    J.block<3, 3>(12, 6) = I3;
    Eigen::Map<Eigen::Matrix<double, 15, 9, Eigen::RowMajor>> out(jacobians[3]);
    out = L_inv * J;
  }
  return true;
}

Eigen::Vector3d tiltedGravity(const double* tilt, double g_norm,
                              Eigen::Matrix<double, 3, 2>* jacobian) {
  const Eigen::Vector3d phi(tilt[0], tilt[1], 0.0);
  const Eigen::Vector3d g = so3::expMatrix(phi) * Eigen::Vector3d(0.0, 0.0, -g_norm);
  if (jacobian) *jacobian = (-so3::skew(g) * so3::rightJacobian(-phi)).leftCols<2>();
  return g;
}

bool ImuGravityFactor::Evaluate(double const* const* parameters, double* residuals,
                                double** jacobians) const {
  Eigen::Matrix<double, 3, 2> dg_dtilt;
  const bool want_tilt = jacobians != nullptr && jacobians[4] != nullptr;
  const Eigen::Vector3d g =
      tiltedGravity(parameters[4], inner_.gravityNorm(), want_tilt ? &dg_dtilt : nullptr);
  Eigen::Matrix<double, 15, 3, Eigen::RowMajor> dr_dg;
  if (!inner_.evaluateWithGravity(parameters, g, residuals, jacobians,
                                  want_tilt ? dr_dg.data() : nullptr))
    return false;
  if (want_tilt) {
    Eigen::Map<Eigen::Matrix<double, 15, 2, Eigen::RowMajor>> out(jacobians[4]);
    out = dr_dg * dg_dtilt;
  }
  return true;
}

Eigen::Matrix<double, 15, 1> ImuFactor::residual(const ImuState& state_i,
                                                 const ImuState& state_j) const {
  const ImuStateBlocks bi = ImuStateBlocks::fromState(state_i);
  const ImuStateBlocks bj = ImuStateBlocks::fromState(state_j);
  const double* params[4] = {bi.pose, bi.motion, bj.pose, bj.motion};
  Eigen::Matrix<double, 15, 1> whitened;
  Evaluate(params, whitened.data(), nullptr);
  return sqrt_information_.triangularView<Eigen::Lower>().solve(whitened);
}

}  // namespace storey
