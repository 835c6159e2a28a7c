#pragma once
/// What `storey batch` keeps in FLEET_OUT to be resumable and idempotent:
/// per log what its run used (input, calibration, effective config, Storey's
/// version) and how it ended; the plan of a submission (which logs, which run,
/// why); the decision whether to run a log again. Every file is written
/// atomically (common/atomic_file.h), so an interrupted batch never leaves a
/// half-written state behind.
///
///   FLEET_OUT/logs/<name>/          the log's `storey run` output (report.html, ...)
///   FLEET_OUT/state/<name>/config.yaml   the effective configuration of its run
///   FLEET_OUT/state/<name>/state.json    what was used, status, attempts, error, figures
///   FLEET_OUT/state/<name>/run.log       the output of its `storey run` (every attempt)
///   FLEET_OUT/state/plan-<N>.json        submission N: the logs, which to run and why
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fleet_inputs.h"

namespace storey::cli {

/// Where a fleet's files are.
struct FleetPaths {
  std::string root;                                       ///< FLEET_OUT (absolute)
  std::string logOut(const std::string& name) const;      ///< logs/<name>
  std::string stateDir(const std::string& name) const;    ///< state/<name>
  std::string stateFile(const std::string& name) const;   ///< state/<name>/state.json
  std::string configFile(const std::string& name) const;  ///< state/<name>/config.yaml
  std::string runLog(const std::string& name) const;      ///< state/<name>/run.log
  std::string planFile(int submission) const;             ///< state/plan-<N>.json
  std::string slurmDir() const;                           ///< state/slurm
};

/// What a log's run used, as JSON: {"storey_version", "input": {"path",
/// "files": [[relative name, bytes, mtime ns], ...]}, "calibration": {"path",
/// "hash"} or null, "config_hash"}. A log file is identified by its size and
/// modification time (not its content: logs are large), a PCD folder by those
/// of every file in it; calibration and config by an FNV-1a hash of their text.
nlohmann::json usedBy(const FleetLog& log, const std::string& effective_config_yaml);

/// How a log's last run ended (state.json).
struct LogState {
  std::string status;  ///< "running", "done", "failed" or "cancelled"
  nlohmann::json used;
  int attempts = 0;                     ///< runs of `storey run` in the last batch
  std::string error;                    ///< the one-line error of the last failed attempt
  double wall_time_s = 0.0;             ///< of the last attempt [s]
  double peak_memory_mb = 0.0;          ///< of the last attempt [MB]
  std::string started_at, finished_at;  ///< UTC, ISO 8601
  std::string executor;                 ///< "local" or "slurm job <id>_<task>"
  int submission = 0;                   ///< the plan the run belonged to
};
std::optional<LogState> readLogState(const std::string& path);
void writeLogState(const std::string& path, const LogState& state);

/// Why a log runs in this batch; empty when it is skipped. Runs: a log never
/// finished (new, interrupted, cancelled), or whose input, calibration,
/// config or Storey version changed since its last run ("config changed").
/// Skips a log that finished (done, or failed after its retries) with the same
/// `used`. `only_failed`: runs exactly the logs whose last run failed.
/// `force`: runs every log.
std::string whyRun(const std::optional<LogState>& previous, const nlohmann::json& used,
                   bool only_failed, bool force);

/// One log of a plan.
struct PlannedLog {
  FleetLog log;
  nlohmann::json used;
  std::string reason;  ///< why it runs; empty = skipped
};

/// A submission: every log of the batch (for the report), which of them run.
struct FleetPlan {
  std::string fleet_out;  ///< absolute
  int submission = 1;
  int retries = 1;       ///< a failed `storey run` is tried this many more times
  std::string executor;  ///< "local" or "slurm"
  std::vector<PlannedLog> logs;
  std::vector<std::size_t> tasks;  ///< indices into `logs` that run, in task order
  // Slurm only (empty for local):
  std::string job_id;          ///< the array job
  std::string collect_job_id;  ///< the collect job (--submit-only)
};
void writePlan(const FleetPlan& plan);
FleetPlan readPlan(const std::string& path);
/// The newest plan in FLEET_OUT (nullopt when there is none).
std::optional<FleetPlan> latestPlan(const std::string& fleet_out);

/// Current UTC time as ISO 8601 ("2024-05-01T12:00:00Z").
std::string utcNow();

}  // namespace storey::cli
