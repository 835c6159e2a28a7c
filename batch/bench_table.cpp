#include "bench_table.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/statistics.h"
#include "sim/building_spec.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::optional<Json> readJson(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  Json j = Json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  return j;
}

/// The number at a path of keys (array elements by index), if it is one.
std::optional<double> numberAt(const Json& j, std::initializer_list<const char*> keys) {
  const Json* node = &j;
  for (const char* key : keys) {
    if (!node->is_object() || !node->contains(key)) return std::nullopt;
    node = &(*node)[key];
  }
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}

/// The translation RMSE of an eval.json's ATE with this alignment ("se3", "none").
std::optional<double> ateOf(const Json& eval, const std::string& alignment) {
  if (!eval.contains("ate") || !eval["ate"].is_array()) return std::nullopt;
  for (const Json& a : eval["ate"])
    if (a.is_object() && a.value("alignment", "") == alignment)
      return numberAt(a, {"translation_m", "rmse"});
  return std::nullopt;
}

void fail(BenchRow& row, const std::string& what) {
  if (row.error.empty()) row.error = what;
}

void readSpec(const fs::path& path, BenchRow& row) {
  try {
    const sim::BuildingSpec spec = sim::loadBuildingSpec(path.string());
    const auto& b = spec.building;
    row.storeys = static_cast<int>(b.storey_heights.size());
    row.wings = b.wings;
    row.min_storey_height = *std::min_element(b.storey_heights.begin(), b.storey_heights.end());
    row.max_storey_height = *std::max_element(b.storey_heights.begin(), b.storey_heights.end());
    row.stair_slope_deg = std::atan2(b.stairwell.riser, b.stairwell.tread) * 180.0 / M_PI;
    row.lidar = toString(spec.sensors.lidar.model);
    row.motion = sim::toString(spec.robot.motion);
    const Eigen::Vector3d axis = spec.sensors.T_body_lidar.rotation() * Eigen::Vector3d::UnitZ();
    row.lidar_tilt_deg = std::acos(std::clamp(axis.z(), -1.0, 1.0)) * 180.0 / M_PI;
    row.imu_rate_hz = spec.sensors.imu.rate;
    row.imu_grade = spec.sensors.imu.grade ? sim::toString(*spec.sensors.imu.grade) : "custom";
    // The plan: footprint, split levels, single-loaded corridor, atrium,
    // leaning partitions, rooms walked into; "corridor" when none.
    std::vector<std::string> plan;
    const auto& arms = b.arms.positions;
    if (!arms.empty()) {
      const bool at_end = arms[0] == 0.0 || arms[0] == 1.0;
      plan.push_back(arms.size() >= 2 ? "U" : at_end ? "L" : "T");
      if (!b.arms.rises.empty()) plan.push_back("split level");
    }
    if (b.single_loaded) plan.push_back("single-loaded");
    if (b.atrium.rooms > 0) plan.push_back("atrium " + std::to_string(b.atrium.rooms));
    if (std::abs(b.partition_angle - M_PI / 2) > 1e-9) {
      char walls[32];
      std::snprintf(walls, sizeof(walls), "walls %.0f deg", b.partition_angle * 180.0 / M_PI);
      plan.push_back(walls);
    }
    if (spec.robot.rooms_entered > 0)
      plan.push_back(std::to_string(spec.robot.rooms_entered) + " rooms entered");
    for (const std::string& p : plan) row.features += (row.features.empty() ? "" : ", ") + p;
    row.stairs = sim::toString(b.stairwell.kind);
    if (b.stairwell.width >= 4.0) row.stairs += " wide";
  } catch (const Error& e) {
    fail(row, e.what());
  }
}

std::string cell(const std::optional<double>& v, int decimals) {
  if (!v) return "–";
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, *v);
  return text;
}

Json jsonOf(const std::optional<double>& v) {
  return v ? Json(*v) : Json(nullptr);
}

}  // namespace

std::optional<double> worstStoreyHeightError(const std::vector<std::pair<int, double>>& errors) {
  std::vector<std::pair<int, double>> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  std::optional<double> worst;
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i].first != sorted[i - 1].first + 1) continue;
    const double e = std::abs(sorted[i].second - sorted[i - 1].second);
    if (!worst || e > *worst) worst = e;
  }
  return worst;
}

void readBenchRow(const std::string& seed_dir, BenchRow& row) {
  const fs::path dir(seed_dir);
  readSpec(dir / "sim" / "spec.yaml", row);
  if (const std::optional<Json> report = readJson(dir / "run" / "report.json")) {
    const std::optional<double> log = numberAt(*report, {"log_duration_s"});
    const std::optional<double> wall = numberAt(*report, {"wall_time_s_total"});
    row.duration_s = log;
    if (log && wall && *wall > 0.0) row.real_time_factor = *log / *wall;
  } else {
    fail(row, "no run/report.json");
  }
  const std::optional<Json> eval = readJson(dir / "eval.json");
  if (!eval) return fail(row, "no eval.json");
  row.path_m = numberAt(*eval, {"association", "gt_path_length_m"});
  row.end_drift_m = numberAt(*eval, {"drift", "estimate", "dxyz_m"});
  row.ate_m = ateOf(*eval, "se3");
  row.ate_unaligned_m = ateOf(*eval, "none");
  if ((*eval)["storeys"].is_object()) {
    const Json& s = (*eval)["storeys"];
    row.worst_floor_m = numberAt(s, {"max_abs_error_m"});
    if (s.contains("estimated_storeys") && s["estimated_storeys"].is_number_integer())
      row.storeys_found = s["estimated_storeys"].get<int>();
    std::vector<std::pair<int, double>> errors;
    if (s.contains("storeys") && s["storeys"].is_array()) {
      for (const Json& m : s["storeys"])
        if (m.contains("true_index") && m["error_m"].is_number())
          errors.emplace_back(m["true_index"].get<int>(), m["error_m"].get<double>());
    }
    row.worst_height_m = worstStoreyHeightError(errors);
  }
  row.map_median_m = numberAt(*eval, {"map", "distance_m", "median"});
  if (const std::optional<Json> odometry = readJson(dir / "eval_odometry.json"))
    row.odometry_ate_m = ateOf(*odometry, "se3");
  if (const std::optional<Json> planes = readJson(dir / "eval_planes.json"))
    row.wrong_matches = numberAt(*planes, {"planes", "off_their_plane_not_down_weighted"});
}

std::string seedRecordJson(const BenchRow& row, double max_duration, const std::string& config) {
  return Json{{"format", "storey-bench-seed"},
              {"version", 1},
              {"seed", row.seed},
              {"max_duration_s", max_duration},
              {"config", config},
              {"error", row.error.empty() ? Json(nullptr) : Json(row.error)},
              {"peak_memory_mb", jsonOf(row.peak_memory_mb)}}
             .dump(2) +
         "\n";
}

bool readSeedRecord(const std::string& seed_dir, std::uint64_t seed, double max_duration,
                    const std::string& config, BenchRow& row) {
  const std::optional<Json> record = readJson(fs::path(seed_dir) / "seed.json");
  if (!record || record->value("format", "") != "storey-bench-seed") return false;
  const Json& s = (*record)["seed"];
  const std::optional<double> duration = numberAt(*record, {"max_duration_s"});
  if (!s.is_number_unsigned() || s.get<std::uint64_t>() != seed || !duration ||
      *duration != max_duration)
    return false;
  const Json& recorded_config = record->contains("config") ? (*record)["config"] : Json("");
  if (!recorded_config.is_string() || recorded_config.get<std::string>() != config) return false;
  BenchRow kept;
  kept.seed = seed;
  if ((*record)["error"].is_string()) kept.error = (*record)["error"].get<std::string>();
  kept.peak_memory_mb = numberAt(*record, {"peak_memory_mb"});
  readBenchRow(seed_dir, kept);
  row = kept;
  return true;
}

Distribution distributionOf(const std::vector<std::optional<double>>& values,
                            bool higher_is_better) {
  std::vector<double> present;
  for (const std::optional<double>& v : values)
    if (v) present.push_back(*v);
  Distribution d;
  d.count = present.size();
  if (present.empty()) return d;
  d.median = quantile(present, 0.5);
  d.p90 = quantile(present, higher_is_better ? 0.1 : 0.9);
  d.worst = higher_is_better ? *std::min_element(present.begin(), present.end())
                             : *std::max_element(present.begin(), present.end());
  return d;
}

namespace {

struct Column {
  const char* title;
  std::optional<double> BenchRow::*member;
  int decimals;
  bool higher_is_better;
};

const Column kColumns[] = {
    {"path m", &BenchRow::path_m, 0, false},
    {"ATE m", &BenchRow::ate_m, 3, false},
    {"ATE unaligned m", &BenchRow::ate_unaligned_m, 3, false},
    {"odometry ATE m", &BenchRow::odometry_ate_m, 3, false},
    {"end drift m", &BenchRow::end_drift_m, 3, false},
    {"worst floor m", &BenchRow::worst_floor_m, 3, false},
    {"worst height m", &BenchRow::worst_height_m, 3, false},
    {"map median m", &BenchRow::map_median_m, 4, false},
    {"wrong matches", &BenchRow::wrong_matches, 0, false},
    {"RT factor", &BenchRow::real_time_factor, 1, true},
    {"peak MB", &BenchRow::peak_memory_mb, 0, false},
};

}  // namespace

std::string benchMarkdown(const std::vector<BenchRow>& rows, const std::string& title) {
  std::ostringstream md;
  md << "### " << title << "\n\n";
  md << "| seed | storeys (found) | wings | plan | storey m | stairs (deg) | LiDAR (tilt deg) | "
        "IMU (Hz) | motion";
  for (const Column& c : kColumns) md << " | " << c.title;
  md << " |\n|---:|---:|---:|---|---|---:|---|---|---";
  for (std::size_t i = 0; i < std::size(kColumns); ++i) md << "|---:";
  md << "|\n";
  char text[64];
  for (const BenchRow& r : rows) {
    std::snprintf(text, sizeof(text), "%.1f-%.1f", r.min_storey_height, r.max_storey_height);
    md << "| " << r.seed << " | " << r.storeys << " ("
       << (r.storeys_found ? std::to_string(*r.storeys_found) : "–") << ") | " << r.wings << " | "
       << (r.features.empty() ? "corridor" : r.features) << " | " << text << " | " << r.stairs
       << " (" << cell(r.stair_slope_deg, 0) << ") | " << r.lidar << " ("
       << cell(r.lidar_tilt_deg, 0) << ") | " << r.imu_grade << " (" << cell(r.imu_rate_hz, 0)
       << ") | " << r.motion;
    if (!r.error.empty()) {
      md << " | **failed:** " << r.error;
      for (std::size_t i = 1; i < std::size(kColumns); ++i) md << " | ";
      md << " |\n";
      continue;
    }
    for (const Column& c : kColumns) md << " | " << cell(r.*(c.member), c.decimals);
    md << " |\n";
  }
  md << "\n| over " << rows.size() << " seeds | median | 90th percentile | worst | seeds |\n"
     << "|---|---:|---:|---:|---:|\n";
  for (const Column& c : kColumns) {
    std::vector<std::optional<double>> values;
    for (const BenchRow& r : rows)
      if (r.error.empty()) values.push_back(r.*(c.member));
    const Distribution d = distributionOf(values, c.higher_is_better);
    md << "| " << c.title << " | "
       << cell(d.count ? std::optional<double>(d.median) : std::nullopt, c.decimals) << " | "
       << cell(d.count ? std::optional<double>(d.p90) : std::nullopt, c.decimals) << " | "
       << cell(d.count ? std::optional<double>(d.worst) : std::nullopt, c.decimals) << " | "
       << d.count << " |\n";
  }
  std::size_t failed = 0;
  for (const BenchRow& r : rows) failed += r.error.empty() ? 0 : 1;
  md << "\nFailed seeds: " << failed << " of " << rows.size()
     << ". RT factor: log seconds per wall second of `storey run` (worst = lowest; its "
        "percentile column is the 10th).\n";
  return md.str();
}

std::string benchJson(const std::vector<BenchRow>& rows) {
  Json list = Json::array();
  for (const BenchRow& r : rows) {
    Json j = {{"seed", r.seed},
              {"error", r.error.empty() ? Json(nullptr) : Json(r.error)},
              {"storeys", r.storeys},
              {"storeys_found", r.storeys_found ? Json(*r.storeys_found) : Json(nullptr)},
              {"wings", r.wings},
              {"storey_height_m", {r.min_storey_height, r.max_storey_height}},
              {"stair_slope_deg", r.stair_slope_deg},
              {"stairs", r.stairs},
              {"lidar", r.lidar},
              {"lidar_tilt_deg", r.lidar_tilt_deg},
              {"imu_rate_hz", r.imu_rate_hz},
              {"imu_grade", r.imu_grade},
              {"features", r.features},
              {"motion", r.motion},
              {"duration_s", jsonOf(r.duration_s)}};
    for (const Column& c : kColumns) j[c.title] = jsonOf(r.*(c.member));
    list.push_back(std::move(j));
  }
  Json distribution = Json::object();
  for (const Column& c : kColumns) {
    std::vector<std::optional<double>> values;
    for (const BenchRow& r : rows)
      if (r.error.empty()) values.push_back(r.*(c.member));
    const Distribution d = distributionOf(values, c.higher_is_better);
    distribution[c.title] = {
        {"count", d.count}, {"median", d.median}, {"p90", d.p90}, {"worst", d.worst}};
  }
  return Json{{"format", "storey-bench"},
              {"version", 1},
              {"seeds", list},
              {"distribution", distribution}}
             .dump(2) +
         "\n";
}

}  // namespace storey::cli
