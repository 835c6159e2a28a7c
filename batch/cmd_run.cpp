// `storey run`: the whole pipeline on a log. Only the stages that exist run;
// the command says plainly which stages are missing and exits with status 2,
// so no script mistakes a partial run for a finished map.
#include <iomanip>
#include <iostream>

#include "commands.h"
#include "common/error.h"
#include "io/log_reader.h"
#include "options_config.h"

namespace storey::cli {

int runRun(const RunOptions& options) {
  Config config = configFromOptions(options.common);
  if (options.log_path.empty()) {
    throw Error(
        "no LOG given and the built-in simulated building is not available yet (the simulator "
        "stage is missing); give a ROS1 bag: storey run LOG");
  }
  std::unique_ptr<LogReader> reader = openLog(options.log_path, config);
  std::cerr << "storey run: reading " << reader->describe() << '\n';

  double first_time = 0.0, last_time = 0.0;
  bool any = false;
  LogMessage message;
  while (reader->next(message)) {
    const double t = std::visit([](const auto& m) { return m.time(); }, message);
    if (!any) first_time = t;
    last_time = t;
    any = true;
  }
  const LogReadStats& stats = reader->stats();
  std::cout << "input: " << stats.scans << " scans, " << stats.imu_samples << " IMU samples, "
            << stats.points << " points, " << std::fixed << std::setprecision(2)
            << (last_time - first_time) << " s\n";
  for (const auto& [reason, count] : stats.dropped)
    std::cout << "  dropped " << count << " (" << reason << ")\n";
  std::cerr << "storey run: the log was read and validated; the odometry, back end, map and "
               "export stages are not implemented yet, so no trajectory or map was written\n";
  return 2;
}

}  // namespace storey::cli
