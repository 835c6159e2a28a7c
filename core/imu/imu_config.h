#pragma once
/// Parameters of the IMU stage, defaults in the structs, units beside each
/// field. The sensor's noise model is SensorConfig::imu (types/sensor.h).
namespace storey {

/// Initialisation from a still start (imu_initializer.h).
struct ImuInitConfig {
  /// Length of the still window at the start of the log [s], > 0.
  double still_window = 1.0;
  /// Largest spread of the gyro in the window [rad/s]: RMS over the samples of
  /// |gyro - mean gyro| (all three axes together, so it does not depend on the
  /// mounting). 0.02 rad/s = 1.1 deg/s: above MEMS white noise at 1 kHz and
  /// hand tremor, far below walking (> 0.1 rad/s).
  double max_gyro_std = 0.02;
  /// Largest spread of the accelerometer in the window [m/s^2], RMS of
  /// |accel - mean accel|. 0.2 m/s^2: above MEMS noise and motor vibration
  /// of a standing legged robot, below walking (> 1 m/s^2).
  double max_accel_std = 0.2;
  /// The thresholds above are raised to noise_margin times the spread that
  /// the configured white noise alone gives (density * sqrt(3 * rate)), so a
  /// noisy IMU at rest is never taken as moving [-], >= 1.
  double noise_margin = 3.0;
  /// Largest |mean gyro| taken as bias [rad/s]; more is a steady rotation.
  /// 0.1 rad/s = 5.7 deg/s covers consumer MEMS gyro biases.
  double max_gyro_bias = 0.1;
  /// Largest | |mean accel| - gravity | [m/s^2]; more means the sensor is
  /// accelerating or the accelerometer is not in m/s^2 (e.g. in g).
  double max_gravity_error = 0.8;
  /// true: the accelerometer bias along gravity is set so that |mean accel|
  /// matches the configured gravity (absorbs bias, scale error and local
  /// gravity along the vertical); false: accel bias = 0.
  bool accel_bias_along_gravity = true;

  /// When the log does not start at rest (the still checks above fail):
  /// true initialises from the first motion_window seconds of LiDAR and IMU
  /// while moving (odometry/motion_init.h); false stops with the still
  /// check's error.
  bool motion_start = true;
  /// Scans from the first one used for the in-motion initialisation [s], > 0.
  /// 2 s: a walk accelerates and turns enough to separate gravity from the
  /// motion, and the LiDAR-only registration does not drift yet.
  double motion_window = 2.0;
  /// Fewest scans in that window [-], >= 3.
  int motion_min_scans = 8;

  /// Throws storey::Error naming the first field out of range.
  void validate() const;
};

/// When the odometry re-integrates a preintegration instead of using its
/// first-order bias correction (ImuPreintegration::needsRepropagation).
struct ImuPreintegrationConfig {
  /// Gyro bias change since integration that triggers re-integration [rad/s].
  /// The first-order correction's error grows like (|dbg| * dt)^2 / 2: 5e-7 rad
  /// for 0.01 rad/s over 0.1 s.
  double repropagate_gyro_bias_change = 0.01;
  /// Accel bias change that triggers re-integration [m/s^2]. The deltas are
  /// linear in the accel bias (the correction is exact); only the covariance
  /// depends on it, weakly.
  double repropagate_accel_bias_change = 0.2;

  /// Throws storey::Error naming the first field out of range.
  void validate() const;
};

}  // namespace storey
