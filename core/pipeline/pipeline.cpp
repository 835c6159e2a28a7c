#include "pipeline/pipeline.h"

#include <iomanip>
#include <sstream>

#include "backend/backend.h"
#include "common/error.h"
#include "common/log.h"
#include "common/memory.h"
#include "common/stopwatch.h"
#include "io/imu_guard.h"
#include "io/log_reader.h"
#include "io/read_ahead_log_reader.h"
#include "map/map_scan_selector.h"
#include "odometry/odometry.h"
#include "pipeline/map_stage.h"
#include "pipeline/run_outputs.h"
#include "pipeline/run_report.h"
#include "pipeline/stream_log.h"

namespace storey {

PipelineResult runPipeline(const std::string& log_path, const Config& config,
                           const std::string& out_dir, const ProgressFn& progress,
                           const LogTimeFn& log_time) {
  config.validate();
  const Stopwatch wall;
  const LogRecorder warnings;  // every warning of the run, for its report
  FaultLog faults;
  std::unique_ptr<LogReader> reader = std::make_unique<GuardedLogReader>(
      openLog(log_path, config.input, config.sensor), config.input, config.sensor.imu, faults);
  if (config.input.read_ahead_scans > 0)
    reader = std::make_unique<ReadAheadLogReader>(std::move(reader), config.input.read_ahead_scans);
  logInfo("reading " + reader->describe());
  auto odometry = std::make_unique<LidarInertialOdometry>(config.odometry, config.sensor);
  std::unique_ptr<Backend> backend = makeBackend(config.backend);
  MapScanSelector map_scans(config.map);
  RunReportBuilder report(config);
  ScanTimings timings;

  // Odometry per scan, back end per keyframe, map scans chosen: one pass.
  Scan last_scan = streamLog(log_path, *reader, *odometry, *backend, map_scans, report, timings,
                             config.backend.queue_scans, progress, log_time);
  if (progress && !progress(1.0, "back end: final optimisation")) throw Cancelled();
  SlamResult slam = backend->finish(last_scan);
  Scan().points.swap(last_scan.points);
  report.setInput(log_path, reader->stats(), odometry->drops());
  const TimeOffsetEstimate time_offset = odometry->timeOffset();
  if (time_offset.detected()) {
    std::ostringstream detail;
    detail << std::setprecision(2) << "the LiDAR's rotations and the gyro's agree best "
           << std::abs(time_offset.offset_s) * 1e3 << " +- " << time_offset.sigma_s * 1e3 << " ms "
           << (time_offset.offset_s > 0 ? "later" : "earlier")
           << " than sensor.time_offset_lidar_to_imu says, over " << time_offset.pairs
           << " scan pairs";
    faults.add(kFaultTimeOffset, {0.0, 0.0, detail.str()}, "IMU-LiDAR time offset",
               "not corrected (the estimate is a lower bound: a third to a half of the offset "
               "on simulated walks); calibrate sensor.time_offset_lidar_to_imu");
  }
  report.setFaults(faults);
  report.setTimeOffset(time_offset, config.sensor.time_offset_lidar_to_imu);
  report.setInitialisation(odometry->initialState(), odometry->initialisation());
  report.setTrajectory(slam.trajectory);
  report.setWallTime(wall.seconds());
  report.setStreamingPeakMemory(peakResidentMiB());
  if (slam.stats) report.setBackend(*slam.stats);
  // The streaming stages are done: their memory (the odometry's local map,
  // the graph, the log's index) goes back before the map stage needs it.
  odometry.reset();
  backend.reset();
  reader.reset();
  returnFreedMemory();

  // The map at the final poses, its storeys, every file.
  createOutputFolder(out_dir);
  PipelineResult result;
  if (map_scans.enabled()) {
    MapStage map = buildMapStage(map_scans, slam, config.storeys, out_dir, progress);
    report.setMap(map);
    result.map = map.map;
    result.storeys = map.storeys.storeys;
    result.files = map.files;
  }
  if (progress && !progress(1.0, "writing outputs")) throw Cancelled();
  report.setTotalWallTime(wall.seconds());
  report.setWarnings(warnings.warnings(), warnings.warningCount());
  result.report_json = writeRunOutputs(out_dir, slam, timings, report, result.files);
  result.odometry = std::move(slam.odometry);
  result.trajectory = std::move(slam.trajectory);
  result.keyframes = std::move(slam.keyframes);
  result.planes = std::move(slam.planes);
  return result;
}

}  // namespace storey
