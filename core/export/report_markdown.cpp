#include "export/report_markdown.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"

namespace storey {

namespace {

using Json = nlohmann::json;

const Json* find(const Json& j, std::initializer_list<const char*> path) {
  const Json* node = &j;
  for (const char* key : path) {
    if (!node->is_object() || !node->contains(key)) return nullptr;
    node = &(*node)[key];
  }
  return node;
}

std::string number(const Json* j, int decimals) {
  if (!j || !j->is_number()) return "–";
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, j->get<double>());
  return text;
}

std::string number(const Json& j, const char* key, int decimals) {
  return number(find(j, {key}), decimals);
}

std::string text(const Json* j) {
  if (!j) return "–";
  if (j->is_string()) return j->get<std::string>();
  return j->dump();
}

/// Rows of {median, p95, mean, max} objects.
void timingRows(std::ostringstream& md, const std::string& prefix, const Json& timing) {
  if (!timing.is_object()) return;
  for (const auto& [name, stats] : timing.items()) {
    if (!stats.is_object() || !stats.contains("median")) continue;
    md << "| " << prefix << name << " | " << number(stats, "median", 2) << " | "
       << number(stats, "p95", 2) << " | " << number(stats, "mean", 2) << " | "
       << number(stats, "max", 2) << " |\n";
  }
}

}  // namespace

std::string reportMarkdown(const std::string& report_json, const std::vector<ReportImage>& images) {
  return reportMarkdown(Json::parse(report_json, nullptr, false), images);
}

std::string reportMarkdown(const Json& report, const std::vector<ReportImage>& images) {
  if (!report.is_object()) throw Error("report.md: the run report is not a JSON object");
  std::ostringstream md;
  md << "# Storey run report\n\n";
  if (const Json* v = find(report, {"storey_version"})) md << "Storey " << text(v) << ".  \n";
  if (const Json* log = find(report, {"input", "log"})) md << "Log: `" << text(log) << "`.  \n";
  md << "Scans read: " << text(find(report, {"input", "scans_read"}))
     << ", processed: " << text(find(report, {"odometry", "scans"})) << ".  \n";
  md << "Log duration " << number(find(report, {"log_duration_s"}), 1) << " s, wall time "
     << number(find(report, {"wall_time_s"}), 1) << " s, real-time factor "
     << number(find(report, {"real_time_factor"}), 2) << ".\n\n";

  if (const Json* d = find(report, {"end_point_drift"}); d && d->is_object() && !d->empty()) {
    constexpr double kDeg = 180.0 / 3.14159265358979323846;
    auto deg = [&](const char* key) {
      const Json* v = find(*d, {key});
      if (!v || !v->is_number()) return std::string("–");
      char t[32];
      std::snprintf(t, sizeof(t), "%.3f", v->get<double>() * kDeg);
      return std::string(t);
    };
    md << "## Table I: end-point drift\n\n"
          "Last pose relative to the first (the walk returns to its start).\n\n"
          "| dX m | dY m | dZ m | dXYZ m | dYaw ° | dPitch ° | dRoll ° | dAngle ° | path m | dXYZ "
          "% of path |\n"
          "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    md << "| " << number(*d, "dX_m", 3) << " | " << number(*d, "dY_m", 3) << " | "
       << number(*d, "dZ_m", 3) << " | " << number(*d, "dXYZ_m", 3) << " | " << deg("dYaw_rad")
       << " | " << deg("dPitch_rad") << " | " << deg("dRoll_rad") << " | " << deg("dAngle_rad")
       << " | " << number(*d, "path_length_m", 1) << " | " << number(*d, "dXYZ_percent_of_path", 3)
       << " |\n\n";
  }

  const Json* odometry_timing = find(report, {"odometry", "timing_ms"});
  // Back end: per keyframe (SRP extraction, association, optimisation).
  const Json* backend_timing = find(report, {"backend", "timing_ms_per_keyframe"});
  if (odometry_timing || backend_timing) {
    md << "## Table II: time per stage (ms)\n\n"
          "| stage | median | p95 | mean | max |\n|---|---:|---:|---:|---:|\n";
    if (odometry_timing) timingRows(md, "odometry: ", *odometry_timing);
    if (backend_timing) timingRows(md, "back end, per keyframe: ", *backend_timing);
    md << "\n";
    if (backend_timing && backend_timing->contains("final_optimisation"))
      md << "Final optimisation of the whole graph: "
         << number(find(*backend_timing, {"final_optimisation"}), 1) << " ms.\n\n";
  }
  if (const Json* backend = find(report, {"backend", "status"}))
    md << "Back end: " << text(backend) << ".\n\n";

  if (const Json* storeys = find(report, {"storeys"}); storeys && storeys->is_array()) {
    md << "## Storeys\n\n";
    if (storeys->empty()) {
      md << "No storey found (no floor slab large enough).\n\n";
    } else {
      md << "| storey | floor m | ceiling m | clear height m | floor to floor m | area m² | points "
            "| stair points |\n"
            "|---:|---:|---:|---:|---:|---:|---:|---:|\n";
      for (const Json& s : *storeys) {
        md << "| " << text(find(s, {"index"})) << " | " << number(s, "floor_elevation", 3) << " | "
           << number(s, "ceiling_elevation", 3) << " | " << number(s, "clear_height", 3) << " | "
           << number(s, "height", 3) << " | " << number(s, "area", 1) << " | "
           << text(find(s, {"points"})) << " | " << text(find(s, {"stair_points"})) << " |\n";
      }
      md << "\n";
    }
  }

  if (const Json* map = find(report, {"map"}); map && map->is_object()) {
    md << "## Map\n\n"
       << text(find(*map, {"points"})) << " points at " << number(find(*map, {"voxel_size_m"}), 3)
       << " m from " << text(find(*map, {"keyframes"}))
       << " scans (the keyframes and the map scans between them).";
    if (const Json* files = find(*map, {"files"}); files && files->is_array()) {
      md << " Files:";
      for (const Json& f : *files) md << " `" << text(&f) << "`";
    }
    md << "\n\n";
  }

  if (!images.empty()) {
    md << "## Renders\n\n";
    for (const ReportImage& image : images) {
      md << "### " << image.title << "\n\n![" << image.title << "](" << image.path << ")\n\n";
      if (!image.caption.empty()) md << image.caption << "\n\n";
    }
  }

  if (const Json* warnings = find(report, {"warnings"});
      warnings && warnings->is_array() && !warnings->empty()) {
    md << "## Warnings\n\n";
    for (const Json& w : *warnings) md << "- " << text(&w) << "\n";
    md << "\n";
  }
  return md.str();
}

void writeReportMarkdown(const std::string& report_json, const std::string& path,
                         const std::vector<ReportImage>& images) {
  writeFileAtomically(path, reportMarkdown(report_json, images));
}

void writeReportMarkdown(const Json& report, const std::string& path,
                         const std::vector<ReportImage>& images) {
  writeFileAtomically(path, reportMarkdown(report, images));
}

}  // namespace storey
