#include "common/parallel_jobs.h"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace storey {

void runJobs(const std::vector<std::function<void()>>& jobs, int threads,
             const std::function<void(std::size_t)>& on_done) {
  const std::size_t helpers = std::min(static_cast<std::size_t>(std::max(threads, 1)), jobs.size());
  if (helpers <= 1) {
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      jobs[i]();
      if (on_done) on_done(i);
    }
    return;
  }
  std::mutex mutex;
  std::condition_variable changed;
  std::size_t next = 0;  // the next job to start
  bool stop = false;
  std::vector<char> done(jobs.size(), 0);
  std::vector<std::exception_ptr> errors(jobs.size());
  const auto work = [&] {
    for (;;) {
      std::size_t i = 0;
      {
        const std::lock_guard<std::mutex> lock(mutex);
        if (stop || next == jobs.size()) return;
        i = next++;
      }
      std::exception_ptr error;
      try {
        jobs[i]();
      } catch (...) {
        error = std::current_exception();
      }
      {
        const std::lock_guard<std::mutex> lock(mutex);
        errors[i] = error;
        done[i] = 1;
        if (error) stop = true;
      }
      changed.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t h = 0; h < helpers; ++h) pool.emplace_back(work);
  // The calling thread reports the jobs in order as they end (it does none
  // itself: on_done may be slow, a progress bar or a GUI).
  std::exception_ptr failure;
  for (std::size_t i = 0; i < jobs.size() && !failure; ++i) {
    {
      std::unique_lock<std::mutex> lock(mutex);
      changed.wait(lock, [&] { return done[i] != 0 || (stop && next <= i); });
      if (!done[i]) break;  // stopped before it started (a later job's error)
      if (errors[i]) {
        failure = errors[i];
        break;
      }
    }
    try {
      if (on_done) on_done(i);
    } catch (...) {
      failure = std::current_exception();
    }
  }
  {
    const std::lock_guard<std::mutex> lock(mutex);
    stop = true;
  }
  for (std::thread& t : pool) t.join();
  if (!failure) {  // an error of a job after the ones reported
    for (const std::exception_ptr& e : errors)
      if (e) {
        failure = e;
        break;
      }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace storey
