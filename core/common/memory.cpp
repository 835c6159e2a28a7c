#include "common/memory.h"

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

double peakResidentMiB() {
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

}  // namespace storey
