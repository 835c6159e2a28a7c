#include "executor_local.h"

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <mutex>
#include <set>
#include <thread>

#include "fleet_task.h"
#include "progress_bar.h"
#include "stop_signals.h"

namespace storey::cli {
namespace {

std::string counts(std::size_t done, std::size_t running, std::size_t failed, std::size_t queued) {
  return std::to_string(done) + " done, " + std::to_string(running) + " running, " +
         std::to_string(failed) + " failed, " + std::to_string(queued) + " queued";
}

}  // namespace

LocalRunSummary runLocal(const FleetPlan& plan, int jobs) {
  StopSignals signals;
  const std::size_t total = plan.tasks.size();
  std::mutex mutex;  // guards the counts and `children`
  std::size_t next = 0, done = 0, failed = 0, running = 0;
  std::set<pid_t> children;
  ProgressBar bar("batch");
  auto show = [&] {  // mutex held
    bar.setDetail(counts(done, running, failed, total - next));
    bar.update(total == 0 ? 1.0 : static_cast<double>(done + failed) / static_cast<double>(total),
               "logs");
  };
  {
    std::lock_guard<std::mutex> lock(mutex);
    show();
  }
  TaskHooks hooks;
  hooks.stop = &StopSignals::flag();
  hooks.started = [&](pid_t pid) {
    std::lock_guard<std::mutex> lock(mutex);
    children.insert(pid);
  };
  hooks.finished = [&](pid_t pid) {
    std::lock_guard<std::mutex> lock(mutex);
    children.erase(pid);
  };
  auto work = [&] {
    for (;;) {
      std::size_t task;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (StopSignals::requested() || next >= total) return;
        task = next++;
        ++running;
        show();
      }
      const PlannedLog& planned = plan.logs[plan.tasks[task]];
      const LogState state = runFleetLog(plan, planned, "local", hooks);
      std::lock_guard<std::mutex> lock(mutex);
      --running;
      if (state.status == "done") ++done;
      if (state.status == "failed") ++failed;
      std::string line = "batch: " + planned.log.name + ": " + state.status;
      if (state.status == "done")
        line += " (" + std::to_string(static_cast<int>(state.wall_time_s + 0.5)) + " s)";
      else if (!state.error.empty())
        line += ": " + state.error;
      bar.print(line);
      show();
    }
  };
  std::vector<std::thread> workers;
  for (int j = 0; j < std::max(1, jobs); ++j) workers.emplace_back(work);
  // The main thread forwards a stop to the running children.
  std::set<pid_t> signalled;
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (running == 0 && (next >= total || StopSignals::requested())) break;
      if (StopSignals::requested())
        for (pid_t pid : children)
          if (signalled.insert(pid).second) kill(pid, SIGTERM);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (std::thread& t : workers) t.join();
  bar.done();
  return {StopSignals::requested()};
}

}  // namespace storey::cli
