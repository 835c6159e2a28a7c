#pragma once
/// The plugin's one way into the core: what a run needs (log, optional
/// config and calibration files, output folder), the run's Config (the core's
/// struct, loaded as `storey run` loads it), and the pipeline call. No Qt and
/// no CloudCompare here: the GUI action and the command-line command both call
/// these functions.
#include <string>
#include <vector>

#include "common/progress.h"
#include "config/config.h"
#include "pipeline/pipeline.h"

namespace storey::plugin {

/// The files of a run, as the surveyor names them.
struct RunRequest {
  std::string log_path;     ///< bag, pcap or PCD folder (required)
  std::string config_path;  ///< YAML configuration; empty = built-in defaults
  std::string
      calibration_path;  ///< sensor calibration; empty = calibration.yaml beside the log, if any
  std::string out_dir;   ///< empty = <log folder>/<log stem>_storey
};

/// The calibration file a run uses: the one given, else `calibration.yaml`
/// in the log's folder when it exists (what `storey simulate` writes), else "".
std::string resolveCalibration(const RunRequest& request);
/// The output folder: the one given, else `<log folder>/<log stem>_storey`.
std::string resolveOutDir(const RunRequest& request);

/// Defaults, then the config file, then the calibration file (resolved as
/// above), exactly as `storey run -c CONFIG --calibration FILE` loads them.
/// Throws storey::Error naming the file and key at fault.
Config loadRequestConfig(const RunRequest& request);

struct RunOutcome {
  PipelineResult result;
  std::string log_path;
  std::string out_dir;           ///< resolved
  std::string calibration_path;  ///< resolved; empty when none was used
  double seconds = 0.0;          ///< wall time of runPipeline [s]
};

/// Checks the log exists, then runs the pipeline (core/pipeline) with
/// `config`. Throws storey::Error (bad input) or storey::Cancelled.
RunOutcome runStorey(const RunRequest& request, const Config& config, const ProgressFn& progress,
                     const LogTimeFn& log_time = nullptr);

/// A line for CloudCompare's console; both faces print them (the GUI action
/// with dispToConsole, -STOREY_SLAM with print and warning).
struct ConsoleLine {
  std::string text;
  bool warning = false;  ///< shown as a CloudCompare warning
};

/// The console after a run: "[Storey] done in S s[: EXTRA]", the run summary
/// (core/pipeline/run_summary.h, what `storey run` prints) as "[Storey]   label:
/// value" lines, then each warning of the run as a warning line.
std::vector<ConsoleLine> runConsoleLines(const RunOutcome& outcome, const std::string& extra = "");

}  // namespace storey::plugin
