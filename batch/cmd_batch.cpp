// `storey batch`: many logs mapped with `storey run`, one output folder each,
// resumable (a finished log is skipped unless what it used changed), on this
// machine (a pool of processes) or on a Slurm cluster (one job array); one
// fleet report at the end. The parts: fleet_inputs (which logs), fleet_state
// (what was used, skip decisions, plans), fleet_task (one log),
// executor_local / executor_slurm, fleet_report (fleet.json, fleet.html).
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <thread>

#include "commands.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "config/config.h"
#include "executor_local.h"
#include "executor_slurm.h"
#include "fleet_inputs.h"
#include "fleet_report.h"
#include "fleet_state.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;

/// Holds an exclusive lock on FLEET_OUT/state/lock: one `storey batch` at a time per fleet.
class FleetLock {
 public:
  explicit FleetLock(const std::string& fleet_out) {
    const std::string path = (fs::path(fleet_out) / "state" / "lock").string();
    fs::create_directories(fs::path(path).parent_path());
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw Error(path + ": cannot open the lock file");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
      throw Error(fleet_out + ": another storey batch is working on this folder");
  }
  ~FleetLock() { ::close(fd_); }
  FleetLock(const FleetLock&) = delete;
  FleetLock& operator=(const FleetLock&) = delete;

 private:
  int fd_ = -1;
};

/// The effective configuration of a log: base config, the log's overrides,
/// then its calibration (which wins for the sensor, as with `storey run`).
std::string effectiveConfig(const Config& base, const FleetLog& log) {
  Config config = base;
  if (!log.config_overrides.empty())
    applyConfigYaml(config, log.config_overrides, log.source + " config");
  if (!log.calibration.empty()) applyCalibrationFile(config, log.calibration);
  return configToYaml(config);
}

SlurmOptions slurmOptionsOf(const BatchOptions& o, const SlurmSettings& manifest) {
  SlurmOptions s;
  s.settings = manifest;
  if (!o.partition.empty()) s.settings.partition = o.partition;
  if (!o.account.empty()) s.settings.account = o.account;
  if (o.cpus_per_task) s.settings.cpus_per_task = o.cpus_per_task;
  if (!o.mem.empty()) s.settings.mem = o.mem;
  if (!o.time.empty()) s.settings.time = o.time;
  if (!o.prolog.empty()) s.settings.prolog = o.prolog;
  s.settings.extra_args.insert(s.settings.extra_args.end(), o.sbatch_args.begin(),
                               o.sbatch_args.end());
  s.max_running = o.jobs;
  s.submit_only = o.submit_only;
  s.storey_binary = o.storey_binary;
  s.poll_seconds = o.poll_seconds;
  return s;
}

/// Finishes the report of `plan` and prints its summary; exit status 1 when a log failed.
int report(const FleetPlan& plan) {
  const nlohmann::json fleet = writeFleetReport(plan);
  std::cout << "storey batch: " << fleetSummaryText(fleet);
  const int failed = fleet["totals"].value("failed", 0) + fleet["totals"].value("cancelled", 0);
  if (failed > 0)
    std::cerr << "storey batch: " << failed << " of " << plan.logs.size()
              << " logs not mapped (errors in " << plan.fleet_out << "/fleet.json)\n";
  return failed > 0 ? 1 : 0;
}

int runStatus(const std::string& dir) {
  const std::string fleet_out = fs::absolute(dir).lexically_normal().string();
  const std::optional<FleetPlan> plan = latestPlan(fleet_out);
  if (!plan) throw Error(dir + ": no storey batch in this folder (no state/plan-*.json)");
  if (plan->executor == "slurm" && slurmJobActive(*plan)) {
    const nlohmann::json fleet = writeFleetReport(*plan);
    std::cout << "storey batch: Slurm job " << plan->job_id << " still running; "
              << fleetSummaryText(fleet);
    return 0;
  }
  if (plan->executor == "slurm") collectSlurm(*plan);
  const nlohmann::json fleet = writeFleetReport(*plan);
  std::cout << "storey batch: " << fleetSummaryText(fleet);
  return 0;
}

}  // namespace

int runBatch(const BatchOptions& options) {
  if (!options.status_dir.empty()) return runStatus(options.status_dir);
  if (options.out_dir.empty()) throw Error("storey batch: -o FLEET_OUT is required");
  if (options.executor != "local" && options.executor != "slurm")
    throw Error("--executor '" + options.executor + "': expected local or slurm");
  if (options.retries < 0) throw Error("--retries must be 0 or more");
  if (options.submit_only && options.executor != "slurm")
    throw Error("--submit-only needs --executor slurm");

  const std::string fleet_out = fs::absolute(options.out_dir).lexically_normal().string();
  fs::create_directories(fleet_out);
  FleetLock lock(fleet_out);
  const std::optional<FleetPlan> previous = latestPlan(fleet_out);
  if (previous && previous->executor == "slurm") {
    if (slurmJobActive(*previous))
      throw Error(fleet_out + ": Slurm job " + previous->job_id +
                  " of the previous submission is "
                  "still running; wait for it (storey batch --status " +
                  fleet_out + ") or cancel it (scancel " + previous->job_id + ")");
    collectSlurm(*previous);  // its last states, before deciding what to run
  }

  const FleetInputs inputs = collectFleetInputs(options.inputs, options.calibration_path);
  const std::string config_path =
      !options.config_path.empty() ? options.config_path : inputs.config_path;
  const Config base = config_path.empty() ? Config{} : loadConfig(config_path);

  FleetPlan plan;
  plan.fleet_out = fleet_out;
  plan.submission = previous ? previous->submission + 1 : 1;
  plan.retries = options.retries;
  plan.executor = options.executor;
  const FleetPaths paths{fleet_out};
  std::map<std::string, int> reasons;
  for (const FleetLog& log : inputs.logs) {
    PlannedLog p;
    p.log = log;
    const std::string yaml = effectiveConfig(base, log);
    p.used = usedBy(log, yaml);
    p.reason =
        whyRun(readLogState(paths.stateFile(log.name)), p.used, options.only_failed, options.force);
    if (!p.reason.empty()) {
      fs::create_directories(paths.stateDir(log.name));
      writeFileAtomically(
          paths.configFile(log.name),
          "# storey batch: the effective configuration of " + log.path + "\n" + yaml + "\n");
      plan.tasks.push_back(plan.logs.size());
      ++reasons[p.reason];
    }
    plan.logs.push_back(std::move(p));
  }
  writePlan(plan);
  std::cerr << "batch: " << plan.logs.size() << " logs, " << plan.tasks.size() << " to run";
  for (const auto& [reason, count] : reasons) std::cerr << (", ") << count << " " << reason;
  std::cerr << "; " << plan.logs.size() - plan.tasks.size() << " skipped (finished before)\n";

  bool stopped = false;
  if (!plan.tasks.empty() && options.executor == "local") {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const int jobs =
        options.jobs > 0 ? options.jobs : std::max(1, static_cast<int>(cores) / kThreadsPerRun);
    std::cerr << "batch: " << jobs << " at a time on this machine, into " << fleet_out << '\n';
    stopped = runLocal(plan, jobs).stopped;
    if (stopped) {  // the logs that never started
      for (std::size_t t : plan.tasks) {
        const PlannedLog& p = plan.logs[t];
        const auto state = readLogState(paths.stateFile(p.log.name));
        if (state && state->submission == plan.submission) continue;
        LogState s;
        s.status = "cancelled";
        s.used = p.used;
        s.submission = plan.submission;
        s.error = "not started: the batch was stopped";
        s.finished_at = utcNow();
        writeLogState(paths.stateFile(p.log.name), s);
      }
    }
  } else if (!plan.tasks.empty()) {
    const SlurmOptions slurm = slurmOptionsOf(options, inputs.slurm);
    submitSlurm(plan, slurm);
    if (options.submit_only) {
      writeFleetReport(plan);
      std::cout << "storey batch: submitted " << plan.tasks.size() << " logs as Slurm job "
                << plan.job_id << " (report by job " << plan.collect_job_id
                << " when it ends); follow with: storey batch --status " << fleet_out << '\n';
      return 0;
    }
    stopped = !followSlurm(plan, slurm.poll_seconds);
    collectSlurm(plan);
  }
  const int status = report(plan);
  if (stopped) {
    std::cerr << "storey batch: stopped; run the same command again to map the rest\n";
    return 1;
  }
  return status;
}

}  // namespace storey::cli
