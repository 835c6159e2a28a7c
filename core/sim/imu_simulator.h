#pragma once
/// IMU simulation: angular rate and specific force of the IMU frame (its own
/// trajectory T_world_imu = T_world_body * T_body_imu, so the lever arm's
/// centripetal and tangential terms are exact), plus white noise
/// (discrete sigma = density * sqrt(rate)) and bias random walk
/// (per-sample step sigma = random_walk / sqrt(rate)).
#include <cstdint>
#include <vector>

#include "sim/building_spec.h"
#include "sim/trajectory.h"
#include "types/imu_sample.h"

namespace storey::sim {

struct ImuSimulation {
  std::vector<ImuSample> samples;  ///< stamps relative to the start of the simulation [ns]
  std::vector<Pose> T_world_imu;   ///< true pose at each sample
  std::vector<Eigen::Vector3d> gyro_bias, accel_bias;  ///< true biases at each sample
};

/// Sample i is at round(i * 1e9 / rate) ns, for every sample within [0, duration].
/// `perfect`: no noise, no biases.
ImuSimulation simulateImu(const Trajectory& trajectory, const SensorsSpec& sensors, double duration,
                          bool perfect, std::uint64_t seed);

/// Stamp of IMU sample i relative to the start [ns].
inline std::int64_t imuSampleNs(std::int64_t i, double rate) {
  return static_cast<std::int64_t>(std::llround(static_cast<double>(i) * 1e9 / rate));
}

}  // namespace storey::sim
