#include "sim/imu_simulator.h"

#include <cmath>

#include "sim/random.h"

namespace storey::sim {

ImuSimulation simulateImu(const Trajectory& trajectory, const SensorsSpec& sensors, double duration,
                          bool perfect, std::uint64_t seed) {
  const ImuSpec& imu = sensors.imu;
  Random rng(seed, 0x1a0000ULL);
  const double sqrt_rate = std::sqrt(imu.rate);
  const double gyro_sigma = perfect ? 0.0 : imu.gyro_noise_density * sqrt_rate;
  const double accel_sigma = perfect ? 0.0 : imu.accel_noise_density * sqrt_rate;
  const double gyro_walk = perfect ? 0.0 : imu.gyro_random_walk / sqrt_rate;
  const double accel_walk = perfect ? 0.0 : imu.accel_random_walk / sqrt_rate;
  Eigen::Vector3d bg = perfect ? Eigen::Vector3d::Zero() : imu.gyro_bias;
  Eigen::Vector3d ba = perfect ? Eigen::Vector3d::Zero() : imu.accel_bias;
  auto noise = [&](double sigma) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) n[i] = rng.normal() * sigma;
    return n;
  };

  ImuSimulation out;
  const std::int64_t end_ns = static_cast<std::int64_t>(std::floor(duration * 1e9));
  for (std::int64_t i = 0;; ++i) {
    const std::int64_t t_ns = imuSampleNs(i, imu.rate);
    if (t_ns > end_ns) break;
    const FrameKinematics k = trajectory.frame(t_ns * 1e-9, sensors.T_body_imu);
    ImuSample sample;
    sample.stamp_ns = t_ns;
    sample.gyro = k.omega_frame + bg + noise(gyro_sigma);
    sample.accel = specificForce(k, imu.gravity) + ba + noise(accel_sigma);
    out.samples.push_back(sample);
    out.T_world_imu.push_back(k.T_world_frame);
    out.gyro_bias.push_back(bg);
    out.accel_bias.push_back(ba);
    bg += noise(gyro_walk);
    ba += noise(accel_walk);
  }
  return out;
}

}  // namespace storey::sim
