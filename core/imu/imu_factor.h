#pragma once
/// Ceres residual of one preintegrated IMU measurement between the states at
/// t_i and t_j (Forster et al., TRO 2017, sec. VI; docs/method/imu.md).
///
/// Parameter blocks (imu_state_blocks.h): pose_i (7), motion_i (9), pose_j (7),
/// motion_j (9). With g = (0, 0, -|g|), Dt = t_j - t_i, the preintegrated
/// deltas dR, dv, dp and bias Jacobians J taken at the linearisation biases
/// (bg0, ba0), and dbg = bg_i - bg0, dba = ba_i - ba0:
///   r_R  = Log( (dR Exp(J^R_g dbg))^T R_i^T R_j )
///   r_v  = R_i^T (v_j - v_i - g Dt) - (dv + J^v_g dbg + J^v_a dba)
///   r_p  = R_i^T (p_j - p_i - v_i Dt - g Dt^2 / 2) - (dp + J^p_g dbg + J^p_a dba)
///   r_bg = bg_j - bg_i
///   r_ba = ba_j - ba_i
/// r = [r_R, r_v, r_p, r_bg, r_ba] is whitened by L^-1, where L L^T = Sigma is
/// the 15x15 covariance of ImuPreintegration (white noise, and bias random
/// walk for the bias rows, correlated with the deltas), so that
/// |L^-1 r|^2 = r^T Sigma^-1 r.
///
/// Jacobians are analytic (Ceres evaluates this factor for every pair of
/// states in every iteration; about 2 us with all Jacobians). They are derived for a left
/// perturbation R <- Exp(a) R (a: rotation vector in the world frame), with Jr the right Jacobian
/// of SO(3) and E = Exp(r_R):
///   dr_R/da_i = -Jr^-1(r_R) R_j^T          dr_R/da_j = Jr^-1(r_R) R_j^T
///   dr_R/dbg_i = -Jr^-1(r_R) E^T Jr(J^R_g dbg) J^R_g
///   dr_v/da_i = R_i^T [v_j - v_i - g Dt]x  dr_p/da_i = R_i^T [p_j - p_i - v_i Dt - g Dt^2/2]x
///   dr_v/dv_i = -R_i^T, dr_v/dv_j = R_i^T, dr_p/dp_i = -R_i^T, dr_p/dp_j = R_i^T,
///   dr_p/dv_i = -R_i^T Dt, dr_{v,p}/db_i = -J^{v,p}_{g,a}, dr_b/db_i = -I, dr_b/db_j = I.
/// Ceres' EigenQuaternionManifold perturbs q by [delta, 1] * q, i.e. a = 2 delta,
/// with PlusJacobian P(q) (4x3, orthonormal columns); the ambient Jacobian
/// returned for the quaternion is 2 (dr/da) P(q)^T, so that (dr/dq) P = dr/ddelta.
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "imu/imu_preintegration.h"
#include "imu/imu_state.h"

namespace storey {

class ImuFactor final : public ceres::SizedCostFunction<15, 7, 9, 7, 9> {
 public:
  /// Copies what it needs from `preintegration` (no reference is kept).
  /// Throws storey::Error when the covariance is not positive definite.
  explicit ImuFactor(const ImuPreintegration& preintegration);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  /// The same with gravity `gravity_world` [m/s^2] in place of (0, 0, -|g|);
  /// with `jacobian_gravity` non-null, also d(whitened r)/d(gravity) (15x3,
  /// row-major): dr_v/dg = -R_i^T Dt, dr_p/dg = -R_i^T Dt^2 / 2.
  bool evaluateWithGravity(double const* const* parameters, const Eigen::Vector3d& gravity_world,
                           double* residuals, double** jacobians, double* jacobian_gravity) const;
  /// |g| of the preintegration's noise model [m/s^2].
  double gravityNorm() const { return gravity_.norm(); }

  /// Residual [r_R [rad], r_v [m/s], r_p [m], r_bg [rad/s], r_ba [m/s^2]]
  /// between two states, not whitened (diagnostics, tests).
  Eigen::Matrix<double, 15, 1> residual(const ImuState& state_i, const ImuState& state_j) const;
  /// L^-1 (lower triangular), with L L^T the covariance: whitened r = L^-1 r.
  const Matrix15d& sqrtInformation() const { return sqrt_information_; }

 private:
  Eigen::Quaterniond dR_;
  Eigen::Vector3d dv_, dp_;
  Eigen::Matrix3d dR_dbg_, dv_dbg_, dv_dba_, dp_dbg_, dp_dba_;
  ImuBias bias_lin_;
  Eigen::Vector3d gravity_;
  double dt_;
  Matrix15d sqrt_information_;
};

/// Gravity in the world (map) frame tilted by t = (t_x, t_y) [rad]:
/// g(t) = Exp([t_x, t_y, 0]) (0, 0, -g_norm); with `jacobian`, dg/dt (3x2),
/// the first two columns of -[g(t)]x Jl([t_x, t_y, 0]) (Jl(phi) = Jr(-phi)).
Eigen::Vector3d tiltedGravity(const double* tilt, double g_norm,
                              Eigen::Matrix<double, 3, 2>* jacobian = nullptr);

/// The IMU factor with gravity's direction as a parameter block: blocks pose_i
/// (7), motion_i (9), pose_j (7), motion_j (9), tilt (2), gravity
/// g = tiltedGravity(tilt). The odometry's world frame is levelled from the
/// still start, where an accelerometer bias orthogonal to gravity cannot be
/// told from a tilt (imu.md, section 1); the map built in that frame keeps the
/// tilt. Estimating gravity's direction in the map frame (as FAST-LIO2 does
/// with its gravity state) keeps the IMU consistent with the map, lets the
/// accelerometer bias be told from the tilt once the sensor turns, and gives
/// the rotation that levels the output.
class ImuGravityFactor final : public ceres::SizedCostFunction<15, 7, 9, 7, 9, 2> {
 public:
  explicit ImuGravityFactor(const ImuPreintegration& preintegration) : inner_(preintegration) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  ImuFactor inner_;
};

}  // namespace storey
