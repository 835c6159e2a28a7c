#pragma once
/// report.md: the run report (report.json) for people. Reads the JSON
/// generically: sections that are absent are left out, so it works before
/// and after the back end and the map stage add theirs. Contents: input and
/// run time; Table I (end-point drift, `end_point_drift`); Table II (timing
/// per stage: `odometry.timing_ms`, and `backend.timing_ms` when present);
/// the storey table (`storeys`); map outputs
/// (`map`); warnings (`warnings`); and, when the render stage gives them,
/// the images (renders/*.png) with a title and a caption each.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace storey {

/// An image embedded in the report; `path` relative to the report's folder.
struct ReportImage {
  std::string path;     ///< e.g. "renders/elevation_front.png"
  std::string title;    ///< heading above the image
  std::string caption;  ///< one paragraph below it; may be empty
};

/// Throws storey::Error when `report_json` is not a JSON object.
std::string reportMarkdown(const std::string& report_json,
                           const std::vector<ReportImage>& images = {});
/// The same for a report already in memory.
std::string reportMarkdown(const nlohmann::json& report,
                           const std::vector<ReportImage>& images = {});
/// Writes reportMarkdown(report_json, images) atomically to `path`.
void writeReportMarkdown(const std::string& report_json, const std::string& path,
                         const std::vector<ReportImage>& images = {});
void writeReportMarkdown(const nlohmann::json& report, const std::string& path,
                         const std::vector<ReportImage>& images = {});

}  // namespace storey
