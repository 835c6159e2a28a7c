#include "options_config.h"

#include "config/config.h"

namespace storey::cli {

Config configFromOptions(const CommonOptions& options) {
  Config config = loadRunConfig(options.config_path, options.calibration_path);
  if (!options.points_topic.empty()) config.input.points_topic = options.points_topic;
  if (!options.imu_topic.empty()) config.input.imu_topic = options.imu_topic;
  if (!options.imu_csv.empty()) config.input.imu_csv = options.imu_csv;
  if (options.imu_csv_time_offset) config.input.imu_csv_time_offset = *options.imu_csv_time_offset;
  if (!options.velodyne_calibration.empty()) {
    config.input.velodyne_calibration = options.velodyne_calibration;
  }
  if (options.velodyne_cut_angle_deg) {
    config.input.velodyne_cut_angle_deg = *options.velodyne_cut_angle_deg;
    config.input.validate();
  }
  return config;
}

}  // namespace storey::cli
