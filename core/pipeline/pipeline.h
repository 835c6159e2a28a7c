#pragma once
/// The whole pipeline on one log, as the paper's method section reads:
/// read -> IMU initialisation -> odometry (deskew, features, joint
/// optimisation) -> [SRP back end] -> outputs. The CLI and the plugin both
/// call this.
#include <string>

#include "common/progress.h"
#include "config/config.h"
#include "trajectory/tum.h"

namespace storey {

struct PipelineResult {
  Trajectory odometry;    ///< front-end pose of the LiDAR per scan (scan header stamps)
  Trajectory trajectory;  ///< final pose per scan (= odometry while the back end is off)
  std::string report_json;  ///< the run report (also written to OUT/report.json)
};

/// Runs the pipeline on `log_path` and writes into `out_dir` (created when
/// missing): odometry.tum, trajectory.tum, report.json. Every file is written
/// atomically and only after the whole log was processed, so a failed run
/// leaves no output behind. Throws storey::Error on bad input.
PipelineResult runPipeline(const std::string& log_path, const Config& config,
                           const std::string& out_dir, const ProgressFn& progress = nullptr);

}  // namespace storey
