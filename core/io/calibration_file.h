#pragma once
/// The sensor calibration file (fixed format, version 1; docs/configuration.md):
/// T_imu_lidar, time_offset_lidar_to_imu, imu noise, lidar model, the
/// optional Velodyne cut angle and optional topics. `storey simulate` writes it; `storey run
/// --calibration` reads it over the configuration (config/config.h, applyCalibrationFile).
#include <string>

#include "types/sensor.h"

namespace storey {

/// What a calibration file holds.
struct Calibration {
  SensorConfig sensor;
  std::string points_topic;  ///< empty = not given (auto-detected)
  std::string imu_topic;     ///< empty = not given (auto-detected)
  /// `lidar.cut_angle_deg`: Velodyne packets are cut into frames at this
  /// azimuth [deg, 0..360) (input.velodyne_cut_angle_deg); 0 = where it wraps.
  double velodyne_cut_angle_deg = 0.0;
};

/// Reads `path` over `base` (absent optional keys keep the values of `base`).
/// Throws storey::Error naming the file, the key at fault and its line for
/// unknown keys, wrong types, a missing T_imu_lidar, a rotation that is not a
/// unit quaternion or a value out of range.
Calibration readCalibrationFile(const std::string& path, const Calibration& base = {});

/// Writes the calibration file atomically (topics only when given, the cut
/// angle only when not 0).
void writeCalibrationFile(const Calibration& calibration, const std::string& path);

}  // namespace storey
