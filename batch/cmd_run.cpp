// `storey run`: the pipeline on a log (or on the built-in simulated building).
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "commands.h"
#include "common/error.h"
#include "options_config.h"
#include "pipeline/pipeline.h"
#include "progress_bar.h"
#include "trajectory/drift.h"

namespace storey::cli {

int runRun(const RunOptions& options) {
  Config config = configFromOptions(options.common);
  if (options.no_srp) config.backend.srp = false;
  if (options.log_path.empty()) {
    throw Error(
        "no LOG given and the built-in simulated building is not wired in yet; give a ROS1 bag: "
        "storey run LOG");
  }
  ProgressBar bar("mapping");
  const PipelineResult result = runPipeline(options.log_path, config, options.out_dir, bar.callback());
  bar.done();
  const EndPointDrift drift = endPointDrift(result.trajectory);
  std::cout << std::fixed << std::setprecision(3) << result.trajectory.size() << " scans, path "
            << drift.path_length << " m, end-point drift " << drift.dxyz << " m ("
            << std::setprecision(2) << drift.percent_of_path() << " % of the path)\n"
            << "output: " << options.out_dir << " (odometry.tum, trajectory.tum, report.json)\n";
  if (config.backend.srp)
    std::cout << "note: the SRP back end is not implemented yet; trajectory.tum is the odometry\n";
  return 0;
}

}  // namespace storey::cli
