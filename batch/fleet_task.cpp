#include "fleet_task.h"

#include <fcntl.h>
#include <stdio.h>  // renameat2
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "child_process.h"
#include "common/error.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;

/// Puts the finished folder `from` at `to`: swapped atomically where the
/// file system can (RENAME_EXCHANGE; not NFS), else the old folder is moved
/// aside first. The old folder is removed.
void replaceFolder(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (!fs::exists(to)) {
    fs::rename(from, to, ec);
    if (ec) throw Error(to.string() + ": cannot move the finished run into place: " + ec.message());
    return;
  }
  if (renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_EXCHANGE) == 0) {
    fs::remove_all(from, ec);  // now the old folder
    return;
  }
  const fs::path old = to.string() + ".old";
  fs::remove_all(old, ec);
  fs::rename(to, old, ec);
  if (!ec) fs::rename(from, to, ec);
  if (ec) throw Error(to.string() + ": cannot move the finished run into place: " + ec.message());
  fs::remove_all(old, ec);
}

/// The one-line error of a failed `storey run` (its "storey: error: ..." line).
std::string errorOf(const std::string& run_log, const ChildResult& result) {
  if (result.exit_code < 0) return "storey run could not be started";
  std::string line = lastLine(run_log);
  const std::string prefix = "storey: error: ";
  if (line.rfind(prefix, 0) == 0) line = line.substr(prefix.size());
  if (result.exit_code > 128)
    return "storey run killed by signal " + std::to_string(result.exit_code - 128) + " (" +
           strsignal(result.exit_code - 128) + "); last output: " + line;
  return line;
}

}  // namespace

LogState runFleetLog(const FleetPlan& plan, const PlannedLog& planned, const std::string& executor,
                     const TaskHooks& hooks) {
  const FleetPaths paths{plan.fleet_out};
  const std::string& name = planned.log.name;
  const fs::path out = paths.logOut(name);
  const fs::path partial =
      out.parent_path() / ("." + name + ".partial-" + std::to_string(getpid()));
  fs::create_directories(out.parent_path());
  fs::create_directories(paths.stateDir(name));
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(out.parent_path(), ec))  // killed runs' leftovers
    if (e.path().filename().string().rfind("." + name + ".partial-", 0) == 0)
      fs::remove_all(e.path(), ec);
  const std::string run_log = paths.runLog(name);
  fs::remove(run_log, ec);

  LogState state;
  state.status = "running";
  state.used = planned.used;
  state.started_at = utcNow();
  state.executor = executor;
  state.submission = plan.submission;
  writeLogState(paths.stateFile(name), state);

  const std::vector<std::string> args{"run", planned.log.path,      "-o", partial.string(),
                                      "-c",  paths.configFile(name)};
  for (int attempt = 1; attempt <= 1 + plan.retries; ++attempt) {
    if (hooks.stop && *hooks.stop) break;
    fs::remove_all(partial, ec);
    std::ofstream(run_log, std::ios::app)
        << "== storey batch: attempt " << attempt << " of " << 1 + plan.retries << ", " << utcNow()
        << ": storey run " << planned.log.path << '\n';
    ChildProcess child("/proc/self/exe", args, run_log);
    if (hooks.started) hooks.started(child.pid());
    const ChildResult result = child.wait();
    if (hooks.finished) hooks.finished(child.pid());
    state.attempts = attempt;
    state.wall_time_s = result.wall_s;
    state.peak_memory_mb = result.peak_mb;
    if (result.exit_code == 0) {
      try {
        replaceFolder(partial, out);
        state.status = "done";
        state.error.clear();
      } catch (const Error& e) {
        state.status = "failed";
        state.error = e.what();
      }
      break;
    }
    state.status = "failed";
    state.error = errorOf(run_log, result);
  }
  if (hooks.stop && *hooks.stop && state.status != "done") {
    state.status = "cancelled";
    state.error = "stopped (Ctrl-C or a signal) before the run finished";
  }
  fs::remove_all(partial, ec);
  state.finished_at = utcNow();
  writeLogState(paths.stateFile(name), state);
  return state;
}

int runBatchTask(const std::string& plan_path, int index) {
  const FleetPlan plan = readPlan(plan_path);
  if (index < 0 || static_cast<std::size_t>(index) >= plan.tasks.size())
    throw Error(plan_path + ": no task " + std::to_string(index) + " (the plan has " +
                std::to_string(plan.tasks.size()) + ")");
  const PlannedLog& planned = plan.logs[plan.tasks[static_cast<std::size_t>(index)]];
  std::string executor = "slurm";
  if (const char* job = std::getenv("SLURM_ARRAY_JOB_ID"))
    executor += std::string(" job ") + job + "_" + std::to_string(index);
  std::cerr << "storey batch-task: " << planned.log.name << ": storey run " << planned.log.path
            << '\n';
  const LogState state = runFleetLog(plan, planned, executor);
  std::cerr << "storey batch-task: " << planned.log.name << ": " << state.status
            << (state.error.empty() ? "" : ": " + state.error) << '\n';
  return state.status == "done" ? 0 : 1;
}

}  // namespace storey::cli
