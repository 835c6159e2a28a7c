#include "pipeline/run_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace storey {

namespace {

using Json = nlohmann::json;

/// printf into a std::string (the summary's numbers have fixed decimals).
template <typename... Args>
std::string format(const char* pattern, Args... args) {
  char text[512];
  std::snprintf(text, sizeof(text), pattern, args...);
  return text;
}

double number(const Json& report, const char* pointer) {
  const Json::json_pointer p(pointer);
  return report.contains(p) && report.at(p).is_number() ? report.at(p).get<double>() : 0.0;
}

std::string storeyLine(const Json& s) {
  double floor = s.value("floor_elevation", 0.0);
  if (std::abs(floor) < 0.005) floor = 0.0;  // "0.00", not "-0.00"
  std::string line = format("floor at %.2f m", floor);
  if (s.contains("clear_height") && s["clear_height"].is_number())
    line += format(", clear height %.2f m", s["clear_height"].get<double>());
  else
    line += ", no ceiling found";
  if (s.contains("height") && s["height"].is_number())
    line += format(", floor to floor %.2f m", s["height"].get<double>());
  line += format(", %.0f m^2", s.value("area", 0.0));
  return line;
}

/// The names in the report's file list that start with `prefix`.
std::vector<std::string> filesStartingWith(const Json& files, const std::string& prefix) {
  std::vector<std::string> names;
  if (files.is_array())
    for (const Json& f : files)
      if (f.is_string() && f.get<std::string>().rfind(prefix, 0) == 0)
        names.push_back(f.get<std::string>());
  return names;
}

/// Those files as "OUT/first, second, ..." (the folder once).
std::string fileList(const Json& files, const std::string& prefix, const std::string& out_dir) {
  const std::vector<std::string> names = filesStartingWith(files, prefix);
  if (names.empty()) return {};
  std::string list = (std::filesystem::path(out_dir) / names.front()).string();
  for (std::size_t i = 1; i < names.size(); ++i) list += ", " + names[i];
  return list;
}

}  // namespace

std::string RunSummary::text(const std::string& indent) const {
  std::size_t width = 0;
  for (const Line& l : lines) width = std::max(width, l.label.size());
  std::string out;
  for (const Line& l : lines)
    out += indent + l.label + std::string(width + 2 - l.label.size(), ' ') + l.value + '\n';
  return out;
}

RunSummary summariseRun(const std::string& report_json, const std::string& out_dir) {
  const Json report = Json::parse(report_json, nullptr, false);
  if (!report.is_object()) throw Error("run summary: the run report is not a JSON object");
  const std::filesystem::path out(out_dir);
  RunSummary s;
  auto add = [&s](std::string label, std::string value) {
    s.lines.push_back({std::move(label), std::move(value)});
  };

  add("log", report.value(Json::json_pointer("/input/log"), std::string("?")));
  add("duration", format("%.1f s of log, %.0f scans", number(report, "/log_duration_s"),
                         number(report, "/odometry/scans")));
  add("path", format("%.1f m", number(report, "/end_point_drift/path_length_m")));
  add("end-point drift",
      format("%.3f m (%.2f %% of the path)", number(report, "/end_point_drift/dXYZ_m"),
             number(report, "/end_point_drift/dXYZ_percent_of_path")));
  if (report.contains(Json::json_pointer("/backend/keyframes")))
    add("back end", format("SRP: %.0f keyframes, %.0f planes", number(report, "/backend/keyframes"),
                           number(report, "/backend/planes")));
  else
    add("back end", "off: the trajectory is the odometry");

  if (!report.contains("map")) {
    add("map", "off (map.enabled: false)");
  } else {
    const Json& storeys = report.contains("storeys") ? report["storeys"] : Json::array();
    if (storeys.empty()) {
      add("storeys", "none found (report.md: map, segmentation)");
    } else {
      add("storeys", std::to_string(storeys.size()) + " found");
      for (const Json& storey : storeys)
        add("  storey " + std::to_string(storey.value("index", 0)), storeyLine(storey));
    }
    add("map", format("%.0f points, voxel %.2f m", number(report, "/map/points"),
                      number(report, "/map/voxel_size_m")));
  }

  add("wall time", format("%.1f s in all; odometry and back end %.1f s, %.1fx real time",
                          number(report, "/wall_time_s_total"), number(report, "/wall_time_s"),
                          number(report, "/real_time_factor")));
  s.warning_count = static_cast<std::size_t>(number(report, "/warning_count"));
  if (report.contains("warnings") && report["warnings"].is_array())
    for (const Json& w : report["warnings"])
      if (w.is_string()) s.warnings.push_back(w.get<std::string>());
  add("warnings", s.warning_count == 0 ? std::string("none")
                                       : std::to_string(s.warning_count) + " (report.md)");

  add("report", (out / "report.html").string());
  const Json files = report.contains("files") ? report["files"] : Json::array();
  if (const std::string map_files = fileList(files, "map.", out_dir); !map_files.empty())
    add("map files", map_files);
  if (const std::size_t n = filesStartingWith(files, "storeys/").size(); n > 0)
    add("storey files", (out / "storeys").string() + "/ (" + std::to_string(n) + " files), " +
                            (out / "storeys.json").string());
  add("trajectory", (out / "trajectory.tum").string());
  return s;
}

}  // namespace storey
