#pragma once
/// Per-scan wall times of a run, written as OUT/timing.csv (docs/outputs.md):
/// how the cost per scan and per keyframe evolves over a log, which the run
/// report's medians cannot show (a long walk: is the last hour as fast as the
/// first minutes?). A few bytes per scan.
#include <string>
#include <vector>

namespace storey {

class ScanTimings {
 public:
  /// One scan of the log, in order: its stamp [s], the odometry's wall time
  /// for it [ms] (OdometryScanStats::ms_total), whether the back end made it
  /// a keyframe, and the back end's wall time for it [ms] (at a keyframe: SRP
  /// extraction, association and the graph solve).
  void add(double time, double odometry_ms, bool keyframe, double backend_ms);
  std::size_t size() const { return rows_.size(); }

  /// Writes the CSV atomically: a header line, then one line per scan
  /// `time,odometry_ms,backend_ms,keyframe` (time as in trajectory.tum).
  void write(const std::string& path) const;

 private:
  struct Row {
    double time, odometry_ms, backend_ms;
    bool keyframe;
  };
  std::vector<Row> rows_;
};

}  // namespace storey
