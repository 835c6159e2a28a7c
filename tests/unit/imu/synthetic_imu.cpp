#include "synthetic_imu.h"

#include <algorithm>
#include <cmath>

namespace storey {
namespace test {

double Sinusoids::value(double t) const {
  double v = rate * t;
  for (const Term& m : terms) v += m.amplitude * std::sin(m.omega * t + m.phase);
  return v;
}
double Sinusoids::d1(double t) const {
  double v = rate;
  for (const Term& m : terms) v += m.amplitude * m.omega * std::cos(m.omega * t + m.phase);
  return v;
}
double Sinusoids::d2(double t) const {
  double v = 0.0;
  for (const Term& m : terms)
    v -= m.amplitude * m.omega * m.omega * std::sin(m.omega * t + m.phase);
  return v;
}

SyntheticTrajectory SyntheticTrajectory::trot(const Eigen::Quaterniond& q_body_imu) {
  constexpr double kTwoPi = 2.0 * M_PI;
  const double gait = kTwoPi * 2.5;  // trot: 2.5 Hz stride, bounce at twice that
  SyntheticTrajectory tr;
  tr.x = {0.8, {{0.01, gait, 0.0}, {0.3, kTwoPi * 0.1, 0.3}}};
  tr.y = {0.0, {{0.5, kTwoPi * 0.15, 0.0}, {0.01, gait, 0.5}}};
  tr.z = {0.0, {{0.004, 2.0 * gait, 0.2}, {0.1, kTwoPi * 0.1, 0.0}}};
  tr.yaw = {0.4, {{0.05, gait, 0.7}}};
  tr.pitch = {0.0, {{0.05, gait, 1.0}, {0.1, kTwoPi * 0.1, 0.4}}};
  tr.roll = {0.0, {{0.06, gait, 2.0}, {0.02, 2.0 * gait, 0.1}}};
  tr.q_body_imu = q_body_imu.normalized();
  return tr;
}

SyntheticTrajectory SyntheticTrajectory::still(const Eigen::Quaterniond& q_world_imu) {
  SyntheticTrajectory tr;
  tr.q_body_imu = q_world_imu.normalized();
  return tr;
}

Eigen::Vector3d SyntheticTrajectory::position(double t) const {
  return {x.value(t), y.value(t), z.value(t)};
}
Eigen::Vector3d SyntheticTrajectory::velocity(double t) const {
  return {x.d1(t), y.d1(t), z.d1(t)};
}
Eigen::Vector3d SyntheticTrajectory::acceleration(double t) const {
  return {x.d2(t), y.d2(t), z.d2(t)};
}

Eigen::Quaterniond SyntheticTrajectory::rotation(double t) const {
  const Eigen::Quaterniond q_world_body =
      Eigen::AngleAxisd(yaw.value(t), Eigen::Vector3d::UnitZ()) *
      Eigen::AngleAxisd(pitch.value(t), Eigen::Vector3d::UnitY()) *
      Eigen::AngleAxisd(roll.value(t), Eigen::Vector3d::UnitX());
  return q_world_body * q_body_imu;
}

Eigen::Vector3d SyntheticTrajectory::angularRate(double t) const {
  // R = Rz Ry Rx: R^T dR/dt = [Rx^T Ry^T yaw' e_z + Rx^T pitch' e_y + roll' e_x]x.
  const Eigen::Matrix3d Rx =
      Eigen::AngleAxisd(roll.value(t), Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d Ry =
      Eigen::AngleAxisd(pitch.value(t), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d w_body =
      Rx.transpose() * Ry.transpose() * (yaw.d1(t) * Eigen::Vector3d::UnitZ()) +
      Rx.transpose() * (pitch.d1(t) * Eigen::Vector3d::UnitY()) +
      roll.d1(t) * Eigen::Vector3d::UnitX();
  return q_body_imu.conjugate() * w_body;
}

ImuState SyntheticTrajectory::state(std::int64_t stamp_ns, const ImuBias& bias) const {
  const double t = secondsSinceBase(stamp_ns);
  ImuState s;
  s.stamp_ns = stamp_ns;
  s.T_world_imu = Pose(rotation(t), position(t));
  s.v_world_imu = velocity(t);
  s.bias = bias;
  return s;
}

std::vector<ImuSample> simulateImu(const SyntheticTrajectory& trajectory, const ImuSimOptions& o,
                                   std::vector<ImuBias>* biases) {
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto noise3 = [&](double std) -> Eigen::Vector3d {
    return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)) * std;
  };
  const Eigen::Vector3d g(0.0, 0.0, -o.noise.gravity);
  const auto count = static_cast<std::int64_t>(std::llround(o.duration * o.rate_hz));
  std::vector<ImuSample> samples;
  samples.reserve(static_cast<std::size_t>(count + 1));
  if (biases != nullptr) biases->clear();
  ImuBias bias = o.bias;
  for (std::int64_t k = 0; k <= count; ++k) {
    ImuSample s;
    s.stamp_ns = kBaseNs + std::llround(static_cast<double>(k) * 1e9 / o.rate_hz);
    const double t = secondsSinceBase(s.stamp_ns);
    const Eigen::Quaterniond q = trajectory.rotation(t);
    s.gyro = trajectory.angularRate(t) + bias.gyro;
    s.accel = q.conjugate() * (trajectory.acceleration(t) - g) + bias.accel;
    if (o.white_noise) {
      s.gyro += noise3(o.noise.gyro_noise_density * std::sqrt(o.rate_hz));
      s.accel += noise3(o.noise.accel_noise_density * std::sqrt(o.rate_hz));
    }
    samples.push_back(s);
    if (biases != nullptr) biases->push_back(bias);
    if (o.bias_walk) {
      bias.gyro += noise3(o.noise.gyro_random_walk / std::sqrt(o.rate_hz));
      bias.accel += noise3(o.noise.accel_random_walk / std::sqrt(o.rate_hz));
    }
  }
  return samples;
}

IntegrationErrorBound integrationErrorBound(const SyntheticTrajectory& tr, double rate_hz,
                                            double t_i, double t_j, double gravity) {
  const double h = 1e-5;
  double max_jerk = 0.0, max_angular_accel = 0.0;
  for (double t = t_i; t <= t_j; t += 1e-3) {
    max_jerk =
        std::max(max_jerk, ((tr.acceleration(t + h) - tr.acceleration(t - h)) / (2 * h)).norm());
    max_angular_accel = std::max(
        max_angular_accel, ((tr.angularRate(t + h) - tr.angularRate(t - h)) / (2 * h)).norm());
  }
  const double dt2_6 = 1.0 / (6.0 * rate_hz * rate_hz);
  const double T = t_j - t_i;
  IntegrationErrorBound b;
  b.rotation = 1.25 * dt2_6 * max_angular_accel;
  b.velocity = 1.25 * dt2_6 * max_jerk + gravity * b.rotation * T;
  b.position = b.velocity * T;
  return b;
}

double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b);
}

}  // namespace test
}  // namespace storey
