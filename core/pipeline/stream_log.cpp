#include "pipeline/stream_log.h"

#include <algorithm>
#include <optional>

#include "common/error.h"
#include "common/ordered_worker.h"
#include "common/stopwatch.h"

namespace storey {

namespace {

/// One final odometry result through the back end into the map selection;
/// its deskewed scan is moved into `last_scan`.
void passOn(OdometryResult& scan, Backend& backend, MapScanSelector& map_scans,
            RunReportBuilder& report, ScanTimings& timings, Scan& last_scan) {
  report.addScan(scan);
  const double time = scan.deskewed.time();
  const Stopwatch backend_watch;
  const BackendDecision decision =
      backend.addScan(time, scan.T_odom_lidar, scan.q_world_odom, scan.deskewed);
  timings.add(time, scan.stats.ms_total, decision.keyframe, 1e3 * backend_watch.seconds());
  map_scans.addScan(scan.deskewed, decision.T_world_lidar, decision.keyframe);
  last_scan = std::move(scan.deskewed);
}

}  // namespace

Scan streamLog(const std::string& log_path, LogReader& reader, LidarInertialOdometry& odometry,
               Backend& backend, MapScanSelector& map_scans, RunReportBuilder& report,
               ScanTimings& timings, int queue_scans, const ProgressFn& progress,
               const LogTimeFn& log_time) {
  // The back end and the map scan selection on a thread of their own: only
  // the odometry's results go to it, nothing comes back.
  Scan last_scan;  // written by the back end's thread, read after it finished
  OrderedWorker<OdometryResult> backend_thread(
      static_cast<std::size_t>(std::max(queue_scans, 0)),
      [&](OdometryResult& scan) { passOn(scan, backend, map_scans, report, timings, last_scan); });
  std::size_t scans = 0;
  OdometryResult result;
  auto drain = [&] {
    while (odometry.nextResult(result)) {
      backend_thread.push(std::move(result));
      result = OdometryResult();
      ++scans;
    }
  };
  LogMessage message;
  std::int64_t messages = 0;
  std::optional<double> first_stamp;  // of the log's first message [s]
  double stamp = 0.0;                 // of the latest message [s]
  while (reader.next(message)) {
    if (auto* scan = std::get_if<Scan>(&message)) {
      stamp = scan->time();
      odometry.addScan(std::move(*scan));
    } else {
      stamp = std::get<ImuSample>(message).time();
      odometry.addImu(std::get<ImuSample>(message));
    }
    if (!first_stamp) first_stamp = stamp;
    drain();
    if (progress && (++messages % 256) == 0) {
      if (log_time) log_time(stamp - *first_stamp);
      const double fraction = reader.progress();
      if (!progress(fraction < 0.0 ? 0.0 : fraction, "odometry")) throw Cancelled();
    }
  }
  odometry.finish();
  drain();
  backend_thread.finish();
  if (scans == 0) {
    throw Error(log_path + ": no scan could be processed (" + std::to_string(reader.stats().scans) +
                " scans read)");
  }
  map_scans.finish(last_scan);
  return last_scan;
}

}  // namespace storey
