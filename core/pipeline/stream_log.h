#pragma once
/// The streaming part of the pipeline: log -> odometry -> back end -> map
/// scan selection, one message at a time (memory bounded by the odometry's
/// window and the back end's graph, not by the log).
#include <string>

#include "backend/backend.h"
#include "common/progress.h"
#include "io/log_reader.h"
#include "map/map_scan_selector.h"
#include "odometry/odometry.h"
#include "pipeline/run_report.h"
#include "pipeline/scan_timings.h"

namespace storey {

/// Reads the whole log: every message into the odometry, every final
/// odometry result into the back end, then its decision into the map scan
/// selection, its counts into the report and its wall times into `timings`. Ends with the odometry
/// flushed and the last map scan in; returns the log's last scan (deskewed) for Backend::finish
/// (only that one is kept: the back end copies no scan that is no keyframe). With `queue_scans` > 0
/// the back end, the map scan selection, the report's counts and `timings` take the results on a
/// thread of their own, up to that many scans behind the odometry (the same results: nothing flows
/// back). With each progress report, `log_time` (when set) gets the log time read so far. Throws
/// storey::Error when no scan could be processed, storey::Cancelled when `progress` returns false.
Scan streamLog(const std::string& log_path, LogReader& reader, LidarInertialOdometry& odometry,
               Backend& backend, MapScanSelector& map_scans, RunReportBuilder& report,
               ScanTimings& timings, int queue_scans, const ProgressFn& progress,
               const LogTimeFn& log_time = nullptr);

}  // namespace storey
