#pragma once
/// The end of a run for people: a few aligned lines (log, duration, path,
/// end-point drift, storeys with floor elevations and heights, map points,
/// wall time and real-time factor, warnings, where report.html and the map
/// files are), read from the run report. `storey run` prints it and the
/// CloudCompare plugin shows it in its console: one text, two faces.
#include <string>
#include <vector>

namespace storey {

struct RunSummary {
  struct Line {
    std::string label;  ///< e.g. "drift", "storey 0"
    std::string value;
  };
  std::vector<Line> lines;
  std::size_t warning_count = 0;      ///< warnings logged during the run
  std::vector<std::string> warnings;  ///< as report.json lists them (the first ones)

  /// The lines as text, values aligned after the longest label, each line
  /// starting with `indent` and ending with '\n'.
  std::string text(const std::string& indent = "  ") const;
};

/// The summary of the run whose report is `report_json` (report.json's
/// text, PipelineResult::report_json) written into `out_dir` (file paths are
/// given inside it). Sections missing from the report (map or storeys off,
/// back end off) say so. Throws storey::Error when `report_json` is not a
/// JSON object.
RunSummary summariseRun(const std::string& report_json, const std::string& out_dir);

}  // namespace storey
