#pragma once
/// report.md: the run report (report.json) for people. Reads the JSON
/// generically: sections that are absent are left out, so it works before
/// and after the back end and the map stage add theirs. Contents: input and
/// run time; Table I (end-point drift, `end_point_drift`); Table II (timing
/// per stage: `odometry.timing_ms`, and `backend.timing_ms` when present);
/// the storey table (`storeys`, as addMapToReport() writes it); map outputs
/// (`map`); warnings (`warnings`).
#include <string>

namespace storey {

/// Throws storey::Error when `report_json` is not a JSON object.
std::string reportMarkdown(const std::string& report_json);
/// Writes reportMarkdown(report_json) atomically to `path`.
void writeReportMarkdown(const std::string& report_json, const std::string& path);

}  // namespace storey
