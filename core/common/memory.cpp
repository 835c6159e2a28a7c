#include "common/memory.h"

#include <algorithm>
#include <atomic>
#include <fstream>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace storey {

void returnFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

namespace {

double readPeakResidentMiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kib = -1.0;
      status >> kib;
      return kib >= 0.0 ? kib / 1024.0 : -1.0;
    }
    std::getline(status, key);
  }
  return -1.0;
}

}  // namespace

double peakResidentMiB() {
  // The kernel counts resident pages per thread and adds them up lazily, so
  // with several threads two readings of VmHWM can dip by a few pages: the
  // highest reading so far is the peak.
  static std::atomic<double> highest{-1.0};
  const double now = readPeakResidentMiB();
  double seen = highest.load();
  while (now > seen && !highest.compare_exchange_weak(seen, now)) {
  }
  return std::max(now, seen);
}

}  // namespace storey
