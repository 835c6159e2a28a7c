#include "pipeline/pipeline.h"

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/log.h"
#include "io/log_reader.h"
#include "odometry/odometry.h"
#include "pipeline/run_report.h"

namespace storey {

PipelineResult runPipeline(const std::string& log_path, const Config& config,
                           const std::string& out_dir, const ProgressFn& progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  std::unique_ptr<LogReader> reader = openLog(log_path, config);
  logInfo("reading " + reader->describe());

  PipelineResult result;
  RunReportBuilder report(config);
  LidarInertialOdometry odometry(config, [&](OdometryResult&& scan) {
    const StampedPose stamped{scan.deskewed.time(), scan.T_world_lidar};
    result.odometry.push_back(stamped);
    report.addScan(scan);
    // The SRP back end (keyframes, plane constraints, graph) will correct
    // these poses; until it exists the final trajectory is the odometry.
    result.trajectory.push_back(stamped);
  });

  LogMessage message;
  std::int64_t messages = 0;
  while (reader->next(message)) {
    if (auto* scan = std::get_if<Scan>(&message)) {
      odometry.addScan(std::move(*scan));
    } else {
      odometry.addImu(std::get<ImuSample>(message));
    }
    if (progress && (++messages % 256) == 0) {
      const double fraction = reader->progress();
      if (!progress(fraction < 0.0 ? 0.0 : fraction, "odometry")) throw Cancelled();
    }
  }
  odometry.finish();
  if (result.odometry.empty()) {
    throw Error(log_path + ": no scan could be processed (" + std::to_string(reader->stats().scans) +
                " scans read)");
  }
  if (progress) progress(1.0, "writing outputs");

  const double wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  report.setInput(log_path, reader->stats(), odometry.drops());
  report.setInitialisation(odometry.initialState());
  report.setTrajectory(result.trajectory);
  report.setWallTime(wall_seconds);
  result.report_json = report.json();

  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw Error(out_dir + ": cannot create the output folder: " + ec.message());
  writeTum((std::filesystem::path(out_dir) / "odometry.tum").string(), result.odometry);
  writeTum((std::filesystem::path(out_dir) / "trajectory.tum").string(), result.trajectory);
  writeFileAtomically((std::filesystem::path(out_dir) / "report.json").string(),
                      result.report_json + "\n");
  return result;
}

}  // namespace storey
