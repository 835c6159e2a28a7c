#include "options_config.h"

#include "config/calibration.h"

namespace storey::cli {

Config configFromOptions(const CommonOptions& options) {
  Config config = loadRunConfig(options.config_path, options.calibration_path);
  if (!options.points_topic.empty()) config.input.points_topic = options.points_topic;
  if (!options.imu_topic.empty()) config.input.imu_topic = options.imu_topic;
  return config;
}

}  // namespace storey::cli
