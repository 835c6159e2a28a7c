#pragma once
/// The run report (report.json): input counts and drops by reason, IMU
/// initialisation, per-stage timings (median, p95, mean), feature and match
/// counts with rejections by reason, degenerate scans, end-point drift (the
/// paper's Table I), the back end's association counts and the paper's Table
/// II, the map stage (map and storeys sections), the files written. Built as
/// one JSON object, written once (run_outputs.h).
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "config/config.h"
#include "imu/imu_state.h"
#include "io/fault_log.h"
#include "io/log_reader.h"
#include "odometry/odometry.h"
#include "pipeline/map_stage.h"
#include "trajectory/tum.h"

namespace storey {

class RunReportBuilder {
 public:
  explicit RunReportBuilder(const Config& config);
  ~RunReportBuilder();
  void addScan(const OdometryResult& scan);
  void setInput(const std::string& log_path, const LogReadStats& stats, const OdometryDrops& drops);
  /// The faults found in the log (report.json "faults", docs/faults.md).
  void setFaults(const FaultLog& faults);
  void setInitialisation(const ImuState& initial_state, const OdometryInitialisation& how);
  /// The IMU-LiDAR time offset the log shows beyond `configured_s` [s].
  void setTimeOffset(const TimeOffsetEstimate& estimate, double configured_s);
  void setTrajectory(const Trajectory& trajectory);
  void setWallTime(double seconds);
  /// The process's peak resident size at the end of the streaming stages [MiB].
  void setStreamingPeakMemory(double mib);
  /// The SRP back end's counts and timings (absent with --no-srp).
  void setBackend(const BackendStats& stats);
  /// The map stage's counts and timings and the storey table.
  void setMap(const MapStage& map);
  /// Wall time of the whole run [s] and the files written (relative to OUT).
  void setTotalWallTime(double seconds);
  void setFiles(const std::vector<std::string>& files);
  /// The warnings logged during the run (the first ones) and how many there were.
  void setWarnings(const std::vector<std::string>& warnings, std::size_t count);
  /// The report.
  nlohmann::json json() const;

 private:
  struct Data;
  std::unique_ptr<Data> data_;
};

}  // namespace storey
