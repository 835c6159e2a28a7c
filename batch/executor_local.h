#pragma once
/// The local executor of `storey batch`: a pool of `jobs` worker threads, each
/// running one log at a time as a child `storey run` (fleet_task.h), with a
/// progress line (done / running / failed / queued, elapsed, time left) and a
/// clean stop on Ctrl-C or SIGTERM: no new log starts, the running children
/// are sent SIGTERM, their logs end "cancelled" and their partial outputs are
/// removed; the report is still written.
#include "fleet_state.h"

namespace storey::cli {

struct LocalRunSummary {
  bool stopped = false;  ///< Ctrl-C / SIGTERM ended the batch early
};

/// Runs the plan's tasks. `jobs` >= 1.
LocalRunSummary runLocal(const FleetPlan& plan, int jobs);

/// Threads one `storey run` keeps busy: the default --jobs is the number of
/// cores divided by this.
constexpr int kThreadsPerRun = 1;

}  // namespace storey::cli
