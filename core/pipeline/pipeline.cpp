#include "pipeline/pipeline.h"

#include <chrono>
#include <filesystem>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "backend/backend.h"
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
  // The SRP back end (keyframes, plane constraints, graph) corrects the
  // odometry after each graph solve; off (--no-srp): trajectory = odometry.
  std::unique_ptr<SrpBackend> backend;
  if (config.backend.srp) backend = std::make_unique<SrpBackend>(config);
  LidarInertialOdometry* front_end = nullptr;
  LidarInertialOdometry odometry(config, [&](OdometryResult&& scan) {
    report.addScan(scan);
    if (backend) {
      if (const std::optional<Pose> correction = backend->addScan(scan))
        front_end->applyCorrection(*correction);
      return;
    }
    const StampedPose stamped{scan.deskewed.time(), scan.T_world_lidar};
    result.odometry.push_back(stamped);
    result.trajectory.push_back(stamped);
  });
  front_end = &odometry;

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
  Trajectory keyframes;
  std::string planes_json;
  if (backend) {
    if (progress) progress(1.0, "back end: final optimisation");
    backend->finish();
    result.odometry = backend->odometry();
    result.trajectory = backend->trajectory();
    keyframes = backend->keyframes();
    planes_json = backend->planesJson();
    report.setBackend(backend->stats());
  }
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
  if (backend) {
    writeTum((std::filesystem::path(out_dir) / "keyframes.tum").string(), keyframes);
    writeFileAtomically((std::filesystem::path(out_dir) / "planes.json").string(), planes_json + "\n");
  }
  writeFileAtomically((std::filesystem::path(out_dir) / "report.json").string(),
                      result.report_json + "\n");
  return result;
}

}  // namespace storey
