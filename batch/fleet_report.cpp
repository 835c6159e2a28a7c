#include "fleet_report.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/version.h"
#include "export/report_html.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr const char* kThumbnail = "renders/elevation_front.png";

Json numberAt(const Json& j, const char* pointer) {
  const Json::json_pointer p(pointer);
  return j.contains(p) && j.at(p).is_number() ? j.at(p) : Json(nullptr);
}

Json readJson(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return Json();
  Json j = Json::parse(in, nullptr, false);
  return j.is_object() ? j : Json();
}

std::string fixed(const Json& v, int decimals, const char* unit = "") {
  if (!v.is_number()) return "–";
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f%s", decimals, v.get<double>(), unit);
  return text;
}

std::string duration(const Json& v) {
  if (!v.is_number()) return "–";
  const long s = static_cast<long>(v.get<double>() + 0.5);
  char text[32];
  if (s >= 3600)
    std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", s / 3600, s % 3600 / 60, s % 60);
  else
    std::snprintf(text, sizeof(text), "%ld:%02ld", s / 60, s % 60);
  return text;
}

constexpr const char* kFleetStyle = R"(
body { max-width: 1500px; }
td img { width: 180px; border: 1px solid #ddd; }
td.status-done { color: #1a7f37; font-weight: bold; }
td.status-failed { color: #c62828; font-weight: bold; }
td.status-running, td.status-queued, td.status-cancelled { color: #9a6700; font-weight: bold; }
td.error, small.error { max-width: 40em; font-family: monospace; font-size: 0.9em; }
small.error { display: inline-block; max-width: 22em; font-weight: normal; color: #444; }
)";

}  // namespace

Json fleetJson(const FleetPlan& plan) {
  const FleetPaths paths{plan.fleet_out};
  Json rows = Json::array(), failures = Json::array();
  Json totals = {
      {"logs", plan.logs.size()}, {"done", 0},   {"failed", 0}, {"running", 0}, {"queued", 0},
      {"cancelled", 0},           {"not_run", 0}};
  double duration_s = 0.0, path_m = 0.0, wall_s = 0.0, peak_mb = 0.0;
  std::int64_t map_points = 0;
  std::vector<bool> runs(plan.logs.size(), false);
  for (std::size_t t : plan.tasks) runs[t] = true;
  for (std::size_t i = 0; i < plan.logs.size(); ++i) {
    const PlannedLog& p = plan.logs[i];
    const std::string& name = p.log.name;
    const auto state = readLogState(paths.stateFile(name));
    std::string status = state ? state->status : "not_run";
    // A log of this submission that has not started yet is queued.
    if (runs[i] && (!state || state->submission != plan.submission)) status = "queued";
    Json row = {
        {"name", name},
        {"log", p.log.path},
        {"status", status},
        {"this_batch", runs[i] ? "run: " + p.reason : "skipped"},
        {"attempts", state ? state->attempts : 0},
        {"error", state && status != "done" ? state->error : ""},
        {"wall_time_s", state && status == "done" ? Json(state->wall_time_s) : Json()},
        {"peak_memory_mb", state && status == "done" ? Json(state->peak_memory_mb) : Json()},
        {"finished_at", state ? state->finished_at : ""},
        {"executor", state ? state->executor : ""},
        {"run_log", "state/" + name + "/run.log"}};
    const fs::path out = paths.logOut(name);
    const Json report = status == "done" ? readJson(out / "report.json") : Json();
    row["log_duration_s"] = numberAt(report, "/log_duration_s");
    row["path_length_m"] = numberAt(report, "/end_point_drift/path_length_m");
    row["end_point_drift_m"] = numberAt(report, "/end_point_drift/dXYZ_m");
    row["storeys_found"] = report.contains("storeys") && report["storeys"].is_array()
                               ? Json(report["storeys"].size())
                               : Json();
    row["map_points"] = numberAt(report, "/map/points");
    row["report"] = status == "done" ? "logs/" + name + "/report.html" : "";
    row["thumbnail"] =
        status == "done" && fs::exists(out / kThumbnail) ? "logs/" + name + "/" + kThumbnail : "";
    totals[totals.contains(status) ? status : "not_run"] =
        totals[totals.contains(status) ? status : "not_run"].get<int>() + 1;
    if (status == "done") {
      duration_s += row["log_duration_s"].is_number() ? row["log_duration_s"].get<double>() : 0.0;
      path_m += row["path_length_m"].is_number() ? row["path_length_m"].get<double>() : 0.0;
      map_points += row["map_points"].is_number() ? row["map_points"].get<std::int64_t>() : 0;
      wall_s += state->wall_time_s;
      peak_mb = std::max(peak_mb, state->peak_memory_mb);
    }
    if (status == "failed" || status == "cancelled")
      failures.push_back({{"name", name},
                          {"log", p.log.path},
                          {"status", status},
                          {"error", row["error"]},
                          {"attempts", row["attempts"]},
                          {"run_log", row["run_log"]}});
    rows.push_back(std::move(row));
  }
  totals["log_duration_s"] = duration_s;
  totals["path_length_m"] = path_m;
  totals["map_points"] = map_points;
  totals["wall_time_s"] = wall_s;
  totals["peak_memory_mb_max"] = peak_mb;
  return {{"format", "storey-fleet"},
          {"version", 1},
          {"storey_version", storeyVersion()},
          {"fleet_out", plan.fleet_out},
          {"written_at", utcNow()},
          {"submission", plan.submission},
          {"executor", plan.executor},
          {"slurm_job", plan.job_id},
          {"logs", rows},
          {"totals", totals},
          {"failures", failures}};
}

std::string fleetHtml(const Json& fleet) {
  std::ostringstream h;
  const Json& t = fleet["totals"];
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<title>Storey fleet report</title>\n<style>" << reportHtmlStyle() << kFleetStyle
    << "</style>\n</head>\n<body>\n<h1>Storey fleet report</h1>\n<p>"
    << htmlEscape(fleet.value("fleet_out", "")) << "<br>" << t.value("logs", 0)
    << (t.value("logs", 0) == 1 ? " log: " : " logs: ") << t.value("done", 0) << " done, "
    << t.value("failed", 0) << " failed";
  for (const char* other : {"running", "queued", "cancelled", "not_run"})
    if (t.value(other, 0) > 0) h << ", " << t.value(other, 0) << " " << other;
  h << ". Executor " << htmlEscape(fleet.value("executor", ""));
  if (!fleet.value("slurm_job", "").empty())
    h << " (Slurm job " << htmlEscape(fleet.value("slurm_job", "")) << ")";
  h << ", submission " << fleet.value("submission", 0) << ", written "
    << htmlEscape(fleet.value("written_at", "")) << " by Storey "
    << htmlEscape(fleet.value("storey_version", "")) << ".</p>\n";

  h << "<h2>Logs</h2>\n<table>\n<tr><th>elevation</th><th>log</th><th>status</th>"
       "<th class=\"r\">log duration</th><th class=\"r\">path [m]</th>"
       "<th class=\"r\">end-point drift [m]</th><th class=\"r\">storeys</th>"
       "<th class=\"r\">map points</th><th class=\"r\">wall time</th>"
       "<th class=\"r\">peak memory [MB]</th></tr>\n";
  for (const Json& r : fleet["logs"]) {
    const std::string status = r.value("status", "");
    h << "<tr><td>";
    const std::string report = r.value("report", ""), thumb = r.value("thumbnail", "");
    if (!thumb.empty())
      h << "<a href=\"" << htmlEscape(report) << "\"><img src=\"" << htmlEscape(thumb)
        << "\" alt=\"elevation of " << htmlEscape(r.value("name", "")) << "\"></a>";
    h << "</td><td>";
    if (!report.empty())
      h << "<a href=\"" << htmlEscape(report) << "\">" << htmlEscape(r.value("name", "")) << "</a>";
    else
      h << htmlEscape(r.value("name", ""));
    h << "<br><small>" << htmlEscape(r.value("log", "")) << "<br>"
      << htmlEscape(r.value("this_batch", "")) << "</small></td>"
      << "<td class=\"status-" << htmlEscape(status) << "\">" << htmlEscape(status);
    if (!r.value("error", "").empty())
      h << "<br><small class=\"error\">" << htmlEscape(r.value("error", "")) << "</small>";
    h << "</td>"
      << "<td class=\"r\">" << duration(r["log_duration_s"]) << "</td>"
      << "<td class=\"r\">" << fixed(r["path_length_m"], 1) << "</td>"
      << "<td class=\"r\">" << fixed(r["end_point_drift_m"], 3) << "</td>"
      << "<td class=\"r\">" << (r["storeys_found"].is_number() ? r["storeys_found"].dump() : "–")
      << "</td><td class=\"r\">" << fixed(r["map_points"], 0) << "</td>"
      << "<td class=\"r\">" << duration(r["wall_time_s"]) << "</td>"
      << "<td class=\"r\">" << fixed(r["peak_memory_mb"], 0) << "</td></tr>\n";
  }
  h << "<tr><th></th><th>total</th><th>" << t.value("done", 0) << " done</th><th class=\"r\">"
    << duration(t["log_duration_s"]) << "</th><th class=\"r\">" << fixed(t["path_length_m"], 1)
    << "</th><th></th><th></th><th class=\"r\">" << fixed(t["map_points"], 0)
    << "</th><th class=\"r\">" << duration(t["wall_time_s"]) << "</th><th class=\"r\">max "
    << fixed(t["peak_memory_mb_max"], 0) << "</th></tr>\n</table>\n";

  h << "<h2>Failures</h2>\n";
  if (fleet["failures"].empty()) {
    h << "<p>None.</p>\n";
  } else {
    h << "<table>\n<tr><th>log</th><th>status</th><th class=\"r\">attempts</th><th>error</th>"
         "<th>output</th></tr>\n";
    for (const Json& f : fleet["failures"])
      h << "<tr><td>" << htmlEscape(f.value("name", "")) << "<br><small>"
        << htmlEscape(f.value("log", "")) << "</small></td><td class=\"status-"
        << htmlEscape(f.value("status", "")) << "\">" << htmlEscape(f.value("status", ""))
        << "</td><td class=\"r\">" << f.value("attempts", 0) << "</td><td class=\"error\">"
        << htmlEscape(f.value("error", "")) << "</td><td><a href=\""
        << htmlEscape(f.value("run_log", "")) << "\">run.log</a></td></tr>\n";
    h << "</table>\n";
  }
  h << "</body>\n</html>\n";
  return h.str();
}

Json writeFleetReport(const FleetPlan& plan) {
  const Json fleet = fleetJson(plan);
  writeFileAtomically((fs::path(plan.fleet_out) / "fleet.json").string(), fleet.dump(2) + "\n");
  writeFileAtomically((fs::path(plan.fleet_out) / "fleet.html").string(), fleetHtml(fleet));
  return fleet;
}

std::string fleetSummaryText(const Json& fleet) {
  const Json& t = fleet["totals"];
  std::ostringstream s;
  s << t.value("logs", 0) << (t.value("logs", 0) == 1 ? " log: " : " logs: ") << t.value("done", 0)
    << " done, " << t.value("failed", 0) << " failed";
  for (const char* other : {"running", "queued", "cancelled", "not_run"})
    if (t.value(other, 0) > 0) s << ", " << t.value(other, 0) << " " << other;
  std::size_t skipped = 0;
  for (const Json& r : fleet["logs"])
    if (r.value("this_batch", "") == "skipped") ++skipped;
  if (skipped > 0) s << " (" << skipped << " skipped: finished before with the same input)";
  s << '\n';
  for (const Json& f : fleet["failures"])
    s << "  " << f.value("status", "") << " " << f.value("name", "") << ": " << f.value("error", "")
      << '\n';
  s << "report: " << fleet.value("fleet_out", "") << "/fleet.html\n";
  return s.str();
}

}  // namespace storey::cli
