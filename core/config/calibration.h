#pragma once
/// The sensor calibration file (fixed format, version 1; see docs/formats.md):
/// T_imu_lidar, time_offset_lidar_to_imu, imu noise, lidar model and optional
/// topics. It overrides the matching values of the configuration.
#include <string>

#include "config/config.h"

namespace storey {

/// Reads `path` and overrides the matching fields of `config` (absent optional
/// keys keep the config's values). Throws storey::Error naming the file, the
/// key at fault and its line for unknown keys, wrong types, a missing
/// T_imu_lidar or a rotation that is not a unit quaternion.
void applyCalibrationFile(Config& config, const std::string& path);

/// The configuration of a run: built-in defaults, then the config file (when
/// `config_path` is not empty), then the calibration file (when not empty).
Config loadRunConfig(const std::string& config_path, const std::string& calibration_path);

/// Writes the calibration file for `config` (sensor + topics) atomically.
void writeCalibrationFile(const Config& config, const std::string& path);

}  // namespace storey
