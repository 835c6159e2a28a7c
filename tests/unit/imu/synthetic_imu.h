#pragma once
/// Test fixture: a smooth trajectory with analytic derivatives (a legged
/// robot's trot: 2.5 Hz sway, 5 Hz bounce, walking forward while turning)
/// and the IMU data it produces. Truth comes from the formulas here, never
/// from the code under test.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

#include "config/config.h"
#include "imu/imu_state.h"
#include "types/imu_sample.h"

namespace storey {
namespace test {

/// c * t + sum_m A_m sin(w_m t + phase_m), with its first two derivatives.
struct Sinusoids {
  struct Term {
    double amplitude, omega, phase;
  };
  double rate = 0.0;
  std::vector<Term> terms;
  double value(double t) const;
  double d1(double t) const;
  double d2(double t) const;
};

class SyntheticTrajectory {
 public:
  /// The trot trajectory; R_body_imu: how the IMU is mounted on the body.
  static SyntheticTrajectory trot(
      const Eigen::Quaterniond& q_body_imu = Eigen::Quaterniond::Identity());
  /// Still: constant pose q_world_imu at the origin.
  static SyntheticTrajectory still(const Eigen::Quaterniond& q_world_imu);

  Eigen::Vector3d position(double t) const;      ///< p_world_imu [m]
  Eigen::Vector3d velocity(double t) const;      ///< [m/s]
  Eigen::Vector3d acceleration(double t) const;  ///< [m/s^2]
  Eigen::Quaterniond rotation(double t) const;   ///< q_world_imu
  Eigen::Vector3d angularRate(double t) const;   ///< IMU frame [rad/s]

  /// Truth at stamp (t = (stamp - base) s), with `bias`.
  ImuState state(std::int64_t stamp_ns, const ImuBias& bias = ImuBias()) const;

  /// Body position (x, y, z) and ZYX Euler angles (yaw, pitch, roll) [rad].
  Sinusoids x, y, z, yaw, pitch, roll;
  Eigen::Quaterniond q_body_imu = Eigen::Quaterniond::Identity();
};

/// Time of the first sample of every generated log [ns]: far from 0 like real
/// epoch stamps, to catch precision loss in double seconds.
constexpr std::int64_t kBaseNs = 1'700'000'000'000'000'000;
inline double secondsSinceBase(std::int64_t stamp_ns) {
  return (stamp_ns - kBaseNs) * 1e-9;
}

struct ImuSimOptions {
  double rate_hz = 400.0;
  double duration = 1.0;     ///< [s] samples at 0, 1/rate, ... up to duration inclusive
  ImuBias bias;              ///< constant bias (start value when random walks are on)
  bool white_noise = false;  ///< add white noise of density noise.*_noise_density
  bool bias_walk = false;    ///< let the bias random-walk with noise.*_random_walk
  ImuNoise noise;
  std::uint32_t seed = 1;
};

/// Samples of the trajectory: gyro = angular rate + bias (+ noise),
/// accel = R^T (a - g) + bias (+ noise), g = (0, 0, -noise.gravity).
/// Per-sample noise std = density * sqrt(rate); bias increments std =
/// random_walk / sqrt(rate). `biases`, when given, receives the bias at each sample.
std::vector<ImuSample> simulateImu(const SyntheticTrajectory& trajectory,
                                   const ImuSimOptions& options,
                                   std::vector<ImuBias>* biases = nullptr);

/// Bound on the discretisation error of the trapezoidal IMU integration
/// between t_i and t_j [s since kBaseNs] at `rate_hz`, derived from the
/// Euler-Maclaurin formula: integrating the piecewise-linear interpolant of
/// samples of a smooth f over [t_i, t_j] errs by -(dt^2/12) (f'(t_j) - f'(t_i))
/// + O(dt^3), so |error| <= dt^2/6 max|f'|. For the rotation f = angular rate
/// (f' = angular acceleration); for the velocity f = R_i^T (a - g) (f' = jerk
/// of the world acceleration), plus gravity seen through the rotation error;
/// the position error is at most the velocity error times T. A factor 1.25
/// covers the O(dt^3) remainder.
struct IntegrationErrorBound {
  double rotation, velocity, position;  ///< [rad], [m/s], [m]
};
IntegrationErrorBound integrationErrorBound(const SyntheticTrajectory& trajectory, double rate_hz,
                                            double t_i, double t_j, double gravity = 9.81);

/// Rotation angle between two quaternions [rad].
double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

}  // namespace test
}  // namespace storey
