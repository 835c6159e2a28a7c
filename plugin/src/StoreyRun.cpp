#include "StoreyRun.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "common/error.h"
#include "config/config.h"
#include "pipeline/run_summary.h"

namespace storey::plugin {

namespace fs = std::filesystem;

std::string resolveCalibration(const RunRequest& request) {
  if (!request.calibration_path.empty()) return request.calibration_path;
  fs::path log(request.log_path);
  if (!log.has_filename()) log = log.parent_path();  // "folder/"
  std::error_code ec;
  // A folder's calibration (a PCD folder, a rosbag2 folder) sits inside it
  // or beside it (as `storey simulate --ros2` writes it); a file's beside it.
  std::vector<fs::path> candidates;
  if (fs::is_directory(log, ec)) candidates.push_back(log / "calibration.yaml");
  candidates.push_back(log.parent_path() / "calibration.yaml");
  for (const fs::path& candidate : candidates)
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
  return std::string();
}

std::string resolveOutDir(const RunRequest& request) {
  if (!request.out_dir.empty()) return request.out_dir;
  fs::path log(request.log_path);
  if (!log.has_filename()) log = log.parent_path();  // "folder/" of a PCD folder
  return (log.parent_path() / (log.stem().string() + "_storey")).string();
}

Config loadRequestConfig(const RunRequest& request) {
  return loadRunConfig(request.config_path, resolveCalibration(request));
}

RunOutcome runStorey(const RunRequest& request, const Config& config, const ProgressFn& progress,
                     const LogTimeFn& log_time) {
  if (request.log_path.empty()) throw Error("no log given");
  std::error_code ec;
  if (!fs::exists(request.log_path, ec)) throw Error(request.log_path + ": no such file or folder");
  RunOutcome outcome;
  outcome.log_path = request.log_path;
  outcome.out_dir = resolveOutDir(request);
  outcome.calibration_path = resolveCalibration(request);
  const auto start = std::chrono::steady_clock::now();
  outcome.result = runPipeline(request.log_path, config, outcome.out_dir, progress, log_time);
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

std::vector<ConsoleLine> runConsoleLines(const RunOutcome& outcome, const std::string& extra) {
  char headline[96];
  std::snprintf(headline, sizeof(headline), "[Storey] done in %.1f s", outcome.seconds);
  std::vector<ConsoleLine> lines{{headline + (extra.empty() ? "" : ": " + extra)}};
  const RunSummary summary = summariseRun(outcome.result.report_json, outcome.out_dir);
  for (const RunSummary::Line& line : summary.lines)
    lines.push_back({"[Storey]   " + line.label + ": " + line.value});
  for (const std::string& warning : summary.warnings)
    lines.push_back({"[Storey] warning: " + warning, true});
  return lines;
}

}  // namespace storey::plugin
