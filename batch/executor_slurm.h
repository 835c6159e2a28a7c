#pragma once
/// The Slurm executor of `storey batch`: one job array per submission
/// (`sbatch --array=0-N%M`), task i running `storey batch-task PLAN i` (a
/// `storey run` on its log, fleet_task.h) with per-task resources; then
/// either following the array with squeue until it has left the queue and
/// collecting, or (--submit-only) a collect job that runs after the array
/// (`--dependency=afterany`). Needs only the Slurm client commands on the
/// submitting host and the storey binary on a file system the nodes share.
#include <cstdint>
#include <optional>
#include <string>

#include "fleet_state.h"

namespace storey::cli {

struct SlurmOptions {
  SlurmSettings settings;      ///< partition, account, cpus, mem, time, extra args, prolog
  int max_running = 0;         ///< --jobs: the array's %M; 0 = no limit
  bool submit_only = false;    ///< submit the array and the collect job, do not wait
  std::string storey_binary;   ///< as the nodes see it; empty = this program's path
  double poll_seconds = 10.0;  ///< squeue interval while following
};

/// Resources a task asks for.
struct SlurmResources {
  int cpus = 1;
  std::string mem;   ///< sbatch --mem, e.g. "2048M"
  std::string time;  ///< sbatch --time, e.g. "0:45:00"
};

/// Memory [MB] one `storey run` needs for a log of `bytes` and `duration_s`
/// seconds (docs/batch.md: measured on the simulated buildings, with margin).
double estimateMemoryMb(std::uint64_t bytes, double duration_s);
/// Wall time [s] one `storey run` may take for a log of `duration_s` seconds.
double estimateTimeSeconds(double duration_s);
/// A log's duration [s]: from a ROS1 bag's chunk index, else guessed from its
/// size (5 MB of log per second, a VLP-16's rate).
double logDurationSeconds(const std::string& path, std::uint64_t bytes);
/// The resources of the plan's tasks: the settings where given, else the
/// estimates for its largest log.
SlurmResources slurmResources(const FleetPlan& plan, const SlurmSettings& settings);

/// Writes the job script, submits the array (and with --submit-only the
/// collect job); records the job ids in the plan (rewritten).
void submitSlurm(FleetPlan& plan, const SlurmOptions& options);

/// Follows the array with squeue until it has left the queue, showing a
/// progress line; Ctrl-C cancels the job (scancel). Returns false when stopped.
bool followSlurm(const FleetPlan& plan, double poll_seconds);

/// Whether the plan's array job still has tasks in the queue; throws
/// storey::Error when squeue fails (no controller reachable).
bool slurmJobActive(const FleetPlan& plan);

/// For every task of the plan without a final state of this submission, asks
/// Slurm (sacct when accounting works, else scontrol) how it ended and records
/// it: failed (TIMEOUT, OUT_OF_MEMORY, NODE_FAIL, ... with the task's output
/// file) or cancelled. Call when the job has left the queue.
void collectSlurm(const FleetPlan& plan);

}  // namespace storey::cli
