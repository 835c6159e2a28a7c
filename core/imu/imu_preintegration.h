#pragma once
/// On-manifold IMU preintegration between two times t_i < t_j (Forster et al.,
/// "On-Manifold Preintegration for Real-Time Visual-Inertial Odometry", TRO
/// 2017), on the piecewise-linear IMU signal of imu_signal.h. Full derivation:
/// docs/method/imu.md.
///
/// With w_k, a_k the knot values minus the linearisation biases bg, ba and
/// dt = t_{k+1} - t_k, each interval is integrated by the trapezoidal
/// (midpoint) rule, exact for a linear rotation rate to O(dt^3) per step:
///   theta_k    = (w_k + w_{k+1}) / 2 * dt
///   dR_{k+1}   = dR_k Exp(theta_k)
///   f_k        = dR_k a_k,  f'_{k+1} = dR_{k+1} a_{k+1}
///   dv_{k+1}   = dv_k + (f_k + f'_{k+1}) / 2 * dt
///   dp_{k+1}   = dp_k + dv_k dt + (2 f_k + f'_{k+1}) / 6 * dt^2
/// (the position weights are exact for a force linear in time). With
/// gravity g = (0, 0, -|g|) and Dt = t_j - t_i the deltas relate the states by
///   R_j = R_i dR,  v_j = v_i + g Dt + R_i dv,  p_j = p_i + v_i Dt + g Dt^2 / 2 + R_i dp.
///
/// Errors are propagated on the 15-vector e = [dphi, dv, dp, dbg, dba]
/// (dR_true = dR Exp(dphi); dbg, dba: drift of the bias from its value at t_i):
///   e_{k+1} = F_k e_k + G_k n_k,  F_k = [A_k B_k; 0 I],  G_k = [B_k 0; 0 I]
/// where A_k (9x9) and B_k (9x6) are the exact derivatives of one step above
/// with respect to [dphi, dv, dp] and to the two biases, and the per-step
/// noise n_k = [gyro, accel white noise, gyro, accel bias increments] has
/// covariance diag(sg^2/dt I, sa^2/dt I, sbg^2 dt I, sba^2 dt I) from the
/// continuous densities of ImuNoise (white noise of density s averaged over
/// dt has variance s^2/dt; a random walk of density s grows by s^2 dt).
/// The bias Jacobians J = d[dphi, dv, dp]/d[bg, ba] obey J_{k+1} = A_k J_k + B_k,
/// so a bias change db corrects the deltas to first order without
/// re-integration (correctedDeltas), exactly for the accel bias.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "imu/imu_config.h"
#include "imu/imu_signal.h"
#include "imu/imu_state.h"
#include "types/sensor.h"

namespace storey {

using Matrix15d = Eigen::Matrix<double, 15, 15>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;

/// Deltas of rotation, velocity and position between t_i and t_j, in the IMU
/// frame at t_i, gravity not included.
struct ImuDeltas {
  Eigen::Quaterniond dR = Eigen::Quaterniond::Identity();  ///< R_i^T R_j
  Eigen::Vector3d dv = Eigen::Vector3d::Zero();            ///< R_i^T (v_j - v_i - g Dt) [m/s]
  Eigen::Vector3d dp = Eigen::Vector3d::Zero();  ///< R_i^T (p_j - p_i - v_i Dt - g Dt^2/2) [m]
};

class ImuPreintegration {
 public:
  /// Integrates `signal` with the biases fixed at `bias_linearisation`.
  /// Cost: about 0.8 us per knot (30 us for 0.1 s at 400 Hz).
  ImuPreintegration(ImuSignal signal, const ImuBias& bias_linearisation, const ImuNoise& noise);
  /// Shorthand: slices [start_ns, end_ns] out of `samples` (see sliceImuSignal) and integrates.
  static ImuPreintegration fromSamples(const std::vector<ImuSample>& samples, std::int64_t start_ns,
                                       std::int64_t end_ns, const ImuBias& bias_linearisation,
                                       const ImuNoise& noise);

  /// Re-integrates the stored signal with new linearisation biases.
  void repropagate(const ImuBias& bias_linearisation);
  /// True when `bias` differs from the linearisation biases by more than the
  /// thresholds of `config` (then call repropagate(bias)).
  bool needsRepropagation(const ImuBias& bias, const ImuPreintegrationConfig& config) const;

  /// Deltas at the linearisation biases.
  const ImuDeltas& deltas() const { return deltas_; }
  /// Deltas for other biases, first order in (bias - linearisation bias):
  /// dR Exp(dR/dbg dbg), dv + dv/dbg dbg + dv/dba dba, dp + ...
  ImuDeltas correctedDeltas(const ImuBias& bias) const;
  /// State at t_j predicted from the state at t_i (its biases used through
  /// correctedDeltas and carried over unchanged). state_i.stamp_ns is not checked.
  ImuState predict(const ImuState& state_i) const;

  /// Covariance of [dphi [rad], dv [m/s], dp [m], bias_gyro drift [rad/s],
  /// bias_accel drift [m/s^2]] over the interval (see the header comment).
  const Matrix15d& covariance() const { return covariance_; }
  /// Bias Jacobians (right perturbation of dR): dR(bg + d) ~= dR Exp(dR_dbg() d).
  const Eigen::Matrix3d& dR_dbg() const { return dR_dbg_; }
  const Eigen::Matrix3d& dv_dbg() const { return dv_dbg_; }  ///< [m/s / (rad/s)]
  const Eigen::Matrix3d& dv_dba() const { return dv_dba_; }  ///< [m/s / (m/s^2)] = [s]
  const Eigen::Matrix3d& dp_dbg() const { return dp_dbg_; }  ///< [m / (rad/s)]
  const Eigen::Matrix3d& dp_dba() const { return dp_dba_; }  ///< [m / (m/s^2)]

  const ImuBias& biasLinearisation() const { return bias_lin_; }
  const ImuNoise& noise() const { return noise_; }
  const ImuSignal& signal() const { return signal_; }
  /// Gravity in the world frame, (0, 0, -noise().gravity) [m/s^2].
  Eigen::Vector3d gravity() const { return gravityWorld(noise_.gravity); }
  std::int64_t startNs() const { return signal_.start_ns; }  ///< t_i [ns]
  std::int64_t endNs() const { return signal_.end_ns; }      ///< t_j [ns]
  double duration() const { return signal_.duration(); }     ///< Dt = t_j - t_i [s]

 private:
  void integrate();

  ImuSignal signal_;
  ImuBias bias_lin_;
  ImuNoise noise_;
  ImuDeltas deltas_;
  Matrix15d covariance_ = Matrix15d::Zero();
  Eigen::Matrix3d dR_dbg_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dv_dbg_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dv_dba_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dp_dbg_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dp_dba_ = Eigen::Matrix3d::Zero();
};

}  // namespace storey
