#pragma once
/// Wall-clock time since construction, and the calling thread's CPU time
/// (timings in reports, not results).
#include <time.h>

#include <chrono>

namespace storey {

class Stopwatch {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// CPU time the calling thread has used [s]: a stage's cost without the time
/// it waited for a core (two threads on two cores with a third reading ahead).
inline double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace storey
