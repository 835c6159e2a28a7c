// `storey registration-bias`: the odometry's LiDAR registration step at the
// true poses of a simulated (or surveyed) walk, core/eval/registration_bias.h.
#include <iostream>

#include "commands.h"
#include "eval/registration_bias.h"
#include "eval/storey_error.h"
#include "io/log_reader.h"
#include "options_config.h"
#include "trajectory/tum.h"

namespace storey::cli {

int runRegistrationBias(const RegistrationBiasOptions& options) {
  const Config config = configFromOptions(options.common);
  const Trajectory truth = readTum(options.gt_path);
  const std::unique_ptr<LogReader> log = openLog(options.log_path, config.input, config.sensor);
  eval::RegistrationBiasOptions bias;
  bias.from = options.from;
  bias.to = options.to;
  bias.truth.max_time_difference = options.max_time_difference;
  Trajectory imu_truth;
  if (!options.gt_imu_path.empty()) {
    imu_truth = readTum(options.gt_imu_path);
    bias.imu_truth = &imu_truth;
    bias.T_imu_lidar = config.sensor.T_imu_lidar;
  }
  if (!options.storeys_path.empty())
    for (const eval::StoreyLevel& level : eval::readTrueStoreys(options.storeys_path))
      bias.floor_elevations.push_back(level.floor_elevation);
  const eval::RegistrationBiasResult result =
      eval::measureRegistrationBias(*log, truth, config.odometry, bias);
  std::cout << eval::registrationBiasTable(result);
  if (!options.csv_path.empty()) {
    eval::writeRegistrationBiasCsv(options.csv_path, result);
    std::cout << "\nWrote " << options.csv_path << "\n";
  }
  return 0;
}

}  // namespace storey::cli
