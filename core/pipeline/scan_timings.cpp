#include "pipeline/scan_timings.h"

#include <cstdio>
#include <ostream>

#include "common/atomic_file.h"

namespace storey {

void ScanTimings::add(double time, double odometry_ms, bool keyframe, double backend_ms) {
  rows_.push_back({time, odometry_ms, backend_ms, keyframe});
}

void ScanTimings::write(const std::string& path) const {
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "time,odometry_ms,backend_ms,keyframe\n";
    char line[96];
    for (const Row& r : rows_) {
      std::snprintf(line, sizeof(line), "%.9f,%.3f,%.3f,%d\n", r.time, r.odometry_ms, r.backend_ms,
                    r.keyframe ? 1 : 0);
      out << line;
    }
  });
}

}  // namespace storey
