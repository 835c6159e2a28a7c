#pragma once
/// The sensor set-up every stage shares: LiDAR model, IMU noise model, the
/// LiDAR-IMU extrinsic and time offset (what a calibration file describes,
/// docs/configuration.md). Plain values; read and written by io/calibration_file.h
/// and config/, validated by SensorConfig::validate().
#include <string>

#include "types/pose.h"

namespace storey {

/// LiDAR models known to the readers (ring elevations, firing timing).
enum class LidarModel { kVlp16, kVlp32c, kHdl32e, kOs1_64, kGeneric };
const char* toString(LidarModel model);
/// Parses "VLP-16", "VLP-32C", "HDL-32E", "OS1-64", "generic"; throws storey::Error otherwise.
LidarModel lidarModelFromString(const std::string& name);

/// Noise model of the IMU (continuous-time densities, as on datasheets).
struct ImuNoise {
  double rate_hz = 400.0;               ///< nominal sample rate [Hz], (0, 10000]
  double gyro_noise_density = 1.75e-4;  ///< [rad/s/sqrt(Hz)]
  double accel_noise_density = 5.9e-4;  ///< [m/s^2/sqrt(Hz)]
  double gyro_random_walk = 1.0e-5;     ///< gyro bias random walk [rad/s^2/sqrt(Hz)]
  double accel_random_walk = 1.0e-4;    ///< accel bias random walk [m/s^3/sqrt(Hz)]
  double gravity = 9.81;                ///< magnitude of gravity [m/s^2]
  /// Across a dropout (samples further apart than imuGapThreshold(), or
  /// filled in) the rate and force are unknown: a white noise of these
  /// densities on top of the sensor's (docs/method/imu.md, "Dropouts"); over
  /// 0.1 s, 1 rad/s and 2 m/s^2 (a walk's or a trot's spread).
  double dropout_gyro_density = 0.3;   ///< [rad/s/sqrt(Hz)]
  double dropout_accel_density = 0.6;  ///< [m/s^2/sqrt(Hz)]
};

/// IMU samples further apart than this are a dropout: 5 nominal periods, and
/// at least 50 ms [s].
double imuGapThreshold(const ImuNoise& imu);

/// The sensor set-up: what a calibration file describes.
struct SensorConfig {
  Pose T_imu_lidar;                       ///< pose of the LiDAR frame in the IMU frame
  double time_offset_lidar_to_imu = 0.0;  ///< [s]; t_imu = t_lidar + offset
  ImuNoise imu;
  LidarModel lidar_model = LidarModel::kVlp16;

  /// Checks value ranges; throws storey::Error naming the key (under `sensor.`) at fault.
  void validate() const;
};

}  // namespace storey
