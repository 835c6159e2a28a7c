#include "imu/imu_preintegration.h"

#include <sstream>
#include <utility>

#include "common/error.h"
#include "imu/so3.h"

namespace storey {
namespace {

using Matrix96 = Eigen::Matrix<double, 9, 6>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// The 9x9 step Jacobian A with respect to [dphi, dv, dp], stored by blocks:
/// A = [Phi 0 0; Avphi I 0; Apphi dt*I I]. apply(X) = A X in 3 3x3 products per column.
struct StepJacobian {
  Eigen::Matrix3d Phi, Avphi, Apphi;
  double dt = 0.0;
  template <int N>
  Eigen::Matrix<double, 9, N> apply(const Eigen::Matrix<double, 9, N>& X) const {
    Eigen::Matrix<double, 9, N> Y;
    const auto X0 = X.template topRows<3>();
    Y.template topRows<3>() = Phi * X0;
    Y.template middleRows<3>(3) = Avphi * X0 + X.template middleRows<3>(3);
    Y.template bottomRows<3>() =
        Apphi * X0 + dt * X.template middleRows<3>(3) + X.template bottomRows<3>();
    return Y;
  }
};

void checkSignal(const ImuSignal& signal) {
  if (signal.knots.size() < 2) throw Error("IMU preintegration needs at least two knots");
  for (std::size_t k = 1; k < signal.knots.size(); ++k) {
    if (!(signal.knots[k].t > signal.knots[k - 1].t)) {
      std::ostringstream os;
      os << "IMU preintegration: knot times must increase strictly; knot " << k << " at "
         << signal.knots[k].t << " s follows " << signal.knots[k - 1].t << " s";
      throw Error(os.str());
    }
  }
}

void checkNoise(const ImuNoise& noise) {
  if (!(noise.gyro_noise_density >= 0.0 && noise.accel_noise_density >= 0.0 &&
        noise.gyro_random_walk >= 0.0 && noise.accel_random_walk >= 0.0 && noise.gravity > 0.0)) {
    throw Error("IMU noise densities and random walks must be >= 0 and gravity > 0");
  }
}

}  // namespace

ImuPreintegration::ImuPreintegration(ImuSignal signal, const ImuBias& bias_linearisation,
                                     const ImuNoise& noise)
    : signal_(std::move(signal)), bias_lin_(bias_linearisation), noise_(noise) {
  checkSignal(signal_);
  checkNoise(noise_);
  integrate();
}

ImuPreintegration ImuPreintegration::fromSamples(const std::vector<ImuSample>& samples,
                                                 std::int64_t start_ns, std::int64_t end_ns,
                                                 const ImuBias& bias_linearisation,
                                                 const ImuNoise& noise) {
  return ImuPreintegration(sliceImuSignal(samples, start_ns, end_ns), bias_linearisation, noise);
}

void ImuPreintegration::repropagate(const ImuBias& bias_linearisation) {
  bias_lin_ = bias_linearisation;
  integrate();
}

bool ImuPreintegration::needsRepropagation(const ImuBias& bias,
                                           const ImuPreintegrationConfig& config) const {
  return (bias.gyro - bias_lin_.gyro).norm() > config.repropagate_gyro_bias_change ||
         (bias.accel - bias_lin_.accel).norm() > config.repropagate_accel_bias_change;
}

void ImuPreintegration::integrate() {
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const double sg2 = noise_.gyro_noise_density * noise_.gyro_noise_density;
  const double sa2 = noise_.accel_noise_density * noise_.accel_noise_density;
  const double sbg2 = noise_.gyro_random_walk * noise_.gyro_random_walk;
  const double sba2 = noise_.accel_random_walk * noise_.accel_random_walk;
  const double gap_threshold = imuGapThreshold(noise_);
  const double dg2 = noise_.dropout_gyro_density * noise_.dropout_gyro_density;
  const double da2 = noise_.dropout_accel_density * noise_.dropout_accel_density;

  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Matrix9d P = Matrix9d::Zero();  // covariance of [dphi, dv, dp]
  Matrix96 C = Matrix96::Zero();  // cross-covariance with the bias drift
  Eigen::Matrix<double, 6, 1> S = Eigen::Matrix<double, 6, 1>::Zero();  // bias drift variances
  Matrix96 J = Matrix96::Zero();  // d[dphi, dv, dp] / d[bg, ba]
  Matrix96 B = Matrix96::Zero();

  Eigen::Matrix3d R0 = I3;
  for (std::size_t k = 0; k + 1 < signal_.knots.size(); ++k) {
    const ImuKnot& k0 = signal_.knots[k];
    const ImuKnot& k1 = signal_.knots[k + 1];
    const double dt = k1.t - k0.t;
    const Eigen::Vector3d w0 = k0.gyro - bias_lin_.gyro;
    const Eigen::Vector3d w1 = k1.gyro - bias_lin_.gyro;
    const Eigen::Vector3d a0 = k0.accel - bias_lin_.accel;
    const Eigen::Vector3d a1 = k1.accel - bias_lin_.accel;

    const Eigen::Vector3d theta = 0.5 * dt * (w0 + w1);
    const Eigen::Quaterniond dq = so3::expQuaternion(theta);
    const Eigen::Matrix3d dR_step_T = dq.toRotationMatrix().transpose();
    const Eigen::Matrix3d Jr_dt = so3::rightJacobian(theta) * dt;
    q = (q * dq).normalized();
    const Eigen::Matrix3d R1 = q.toRotationMatrix();

    // Mean propagation (position first: it uses the old velocity).
    const Eigen::Vector3d f0 = R0 * a0;
    const Eigen::Vector3d f1 = R1 * a1;
    const double dt2_6 = dt * dt / 6.0;
    p += v * dt + dt2_6 * (2.0 * f0 + f1);
    v += 0.5 * dt * (f0 + f1);

    // Step Jacobians A (w.r.t. [dphi, dv, dp]) and B (w.r.t. [bg, ba]):
    //   A = [Phi 0 0; Avphi I 0; Apphi dt*I I],  B = [Bphig 0; Bvg Bva; Bpg Bpa].
    const Eigen::Matrix3d S0 = R0 * so3::skew(a0);
    const Eigen::Matrix3d S1 = R1 * so3::skew(a1);
    const Eigen::Matrix3d S1_dRT = S1 * dR_step_T;
    StepJacobian A;
    A.Phi = dR_step_T;
    A.Avphi = -0.5 * dt * (S0 + S1_dRT);
    A.Apphi = -dt2_6 * (2.0 * S0 + S1_dRT);
    A.dt = dt;
    B.block<3, 3>(0, 0) = -Jr_dt;
    B.block<3, 3>(3, 0) = 0.5 * dt * S1 * Jr_dt;
    B.block<3, 3>(6, 0) = dt2_6 * S1 * Jr_dt;
    B.block<3, 3>(3, 3) = -0.5 * dt * (R0 + R1);
    B.block<3, 3>(6, 3) = -dt2_6 * (2.0 * R0 + R1);

    // Covariance: e' = [A B; 0 I] e + [B 0; 0 I] n, on the blocks
    // [P C; C^T S] (S diagonal):
    //   P' = A P A^T + (A C) B^T + B (A C)^T + B (S + Qwhite) B^T,  C' = A C + B S.
    Eigen::Matrix<double, 6, 1> q_white;
    q_white << sg2 / dt, sg2 / dt, sg2 / dt, sa2 / dt, sa2 / dt, sa2 / dt;
    if (k1.sample_spacing > gap_threshold || k1.dropout) {
      // A dropout: the signal here is an interpolation or filled in, its mean
      // over the step unknown to a white noise of the dropout densities
      // (docs/method/imu.md, "Dropouts").
      q_white.head<3>().array() += dg2 / dt;
      q_white.tail<3>().array() += da2 / dt;
    }
    const Matrix96 AC = A.apply(C);
    const Matrix96 B_SQ = B * (S + q_white).asDiagonal();
    const Matrix9d AP = A.apply(P);
    const Matrix9d APAT = A.apply(Matrix9d(AP.transpose()));
    const Matrix9d cross = AC * B.transpose();
    P = APAT + cross + cross.transpose() + B_SQ * B.transpose();
    C = AC + B * S.asDiagonal();
    S.head<3>().array() += sbg2 * dt;
    S.tail<3>().array() += sba2 * dt;

    J = A.apply(J) + B;
    R0 = R1;
  }

  deltas_.dR = q;
  deltas_.dv = v;
  deltas_.dp = p;
  covariance_.setZero();
  covariance_.topLeftCorner<9, 9>() = 0.5 * (P + P.transpose());
  covariance_.topRightCorner<9, 6>() = C;
  covariance_.bottomLeftCorner<6, 9>() = C.transpose();
  covariance_.bottomRightCorner<6, 6>() = S.asDiagonal();
  dR_dbg_ = J.block<3, 3>(0, 0);
  dv_dbg_ = J.block<3, 3>(3, 0);
  dv_dba_ = J.block<3, 3>(3, 3);
  dp_dbg_ = J.block<3, 3>(6, 0);
  dp_dba_ = J.block<3, 3>(6, 3);
}

ImuDeltas ImuPreintegration::correctedDeltas(const ImuBias& bias) const {
  const Eigen::Vector3d dbg = bias.gyro - bias_lin_.gyro;
  const Eigen::Vector3d dba = bias.accel - bias_lin_.accel;
  ImuDeltas out;
  out.dR = (deltas_.dR * so3::expQuaternion(dR_dbg_ * dbg)).normalized();
  out.dv = deltas_.dv + dv_dbg_ * dbg + dv_dba_ * dba;
  out.dp = deltas_.dp + dp_dbg_ * dbg + dp_dba_ * dba;
  return out;
}

ImuState ImuPreintegration::predict(const ImuState& state_i) const {
  const ImuDeltas d = correctedDeltas(state_i.bias);
  const Eigen::Vector3d g = gravity();
  const double Dt = duration();
  const Eigen::Quaterniond& q_i = state_i.T_world_imu.rotation();
  const Eigen::Vector3d& p_i = state_i.T_world_imu.translation();
  const Eigen::Vector3d& v_i = state_i.v_world_imu;
  ImuState out;
  out.stamp_ns = signal_.end_ns;
  out.T_world_imu = Pose(q_i * d.dR, p_i + v_i * Dt + 0.5 * Dt * Dt * g + q_i * d.dp);
  out.v_world_imu = v_i + g * Dt + q_i * d.dv;
  out.bias = state_i.bias;
  return out;
}

}  // namespace storey
