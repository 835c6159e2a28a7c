#pragma once
/// IMU initialisation from a still start: the first ImuInitConfig::still_window
/// seconds of IMU data must be taken at rest. Over that window:
///   gyro bias  = mean gyro (the true rate is zero);
///   "up" in the IMU frame u = mean accel / |mean accel| (at rest the specific
///   force is R_world_imu^T (0, 0, g) + accel bias);
///   R_world_imu = Ry(pitch) Rx(roll) with pitch = atan2(-u_x, hypot(u_y, u_z)),
///   roll = atan2(u_y, u_z): maps u to world +z, yaw = 0 (ZYX convention: the
///   IMU x axis projected on the horizontal points along world +x). Valid for
///   every mounting, upside down and x vertical included;
///   accel bias: from one attitude only the mean specific force is observed.
///   Its component orthogonal to gravity cannot be told from a tilt and is
///   absorbed in the attitude (bias 0 there; a bias b tilts the estimate by
///   about |b_perp| / g rad). Along gravity, the bias is set to
///   (|mean accel| - g) u (ImuInitConfig::accel_bias_along_gravity) so the
///   initial state reproduces the measured specific force exactly, or to 0;
///   position 0, velocity 0.
/// A start that is not still is a storey::Error that says so.
#include <cstdint>
#include <vector>

#include "imu/imu_config.h"
#include "imu/imu_state.h"
#include "types/imu_sample.h"
#include "types/sensor.h"

namespace storey {

/// What the still window looked like (for the run report).
struct ImuInitStats {
  std::size_t samples = 0;           ///< samples in the window
  std::int64_t window_start_ns = 0;  ///< first sample's stamp [ns]
  std::int64_t window_end_ns = 0;    ///< last sample's stamp [ns]
  double gyro_std = 0.0;             ///< RMS |gyro - mean| [rad/s]
  double accel_std = 0.0;            ///< RMS |accel - mean| [m/s^2]
  double gyro_std_limit = 0.0;       ///< threshold applied (after noise_margin) [rad/s]
  double accel_std_limit = 0.0;      ///< threshold applied (after noise_margin) [m/s^2]
  double mean_accel_norm = 0.0;      ///< |mean accel| [m/s^2]
  Eigen::Vector3d up_imu = Eigen::Vector3d::UnitZ();  ///< world +z in the IMU frame [unit]
};

struct ImuInitResult {
  /// State at the end of the still window: R_world_imu gravity-aligned with
  /// yaw 0, p = 0, v = 0, biases as described above.
  ImuState state;
  ImuInitStats stats;
};

/// Initialises from the first still_window seconds of time-ordered samples
/// (more samples may be passed; only the window is read). Throws
/// storey::Error when the data are shorter than the window, when the window
/// is not still, spins steadily, or its mean specific force is not gravity.
ImuInitResult initializeImuFromStill(const std::vector<ImuSample>& samples, const ImuNoise& noise,
                                     const ImuInitConfig& config = ImuInitConfig());

/// R_world_imu that maps the unit vector up_imu (world +z seen in the IMU
/// frame) to world +z with yaw = 0 (see the header comment).
Eigen::Quaterniond gravityAlignedRotation(const Eigen::Vector3d& up_imu);

}  // namespace storey
