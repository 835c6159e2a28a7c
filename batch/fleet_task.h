#pragma once
/// One log of a batch, the same on every executor: `storey run LOG -o TMP
/// -c state/<name>/config.yaml` (a child process: its wall time and peak
/// memory measured), tried 1 + retries times, its output folder moved into
/// FLEET_OUT/logs/<name> only when the run succeeded (a failed or stopped run
/// never leaves a half-written folder), then state.json written.
/// The Slurm executor's array tasks run it as `storey batch-task PLAN INDEX`.
#include <sys/types.h>

#include <atomic>
#include <functional>
#include <string>

#include "fleet_state.h"

namespace storey::cli {

struct TaskHooks {
  std::function<void(pid_t)> started;       ///< a `storey run` child started
  std::function<void(pid_t)> finished;      ///< it exited
  const std::atomic<bool>* stop = nullptr;  ///< set: no further attempt; the run ends "cancelled"
};

/// Runs `planned` of `plan`; returns (and writes) its final state.
LogState runFleetLog(const FleetPlan& plan, const PlannedLog& planned, const std::string& executor,
                     const TaskHooks& hooks = {});

/// `storey batch-task PLAN INDEX`: task INDEX of the plan's tasks (a Slurm
/// array task). Exit status 0 when the log was mapped, 1 when it failed.
int runBatchTask(const std::string& plan_path, int index);

}  // namespace storey::cli
