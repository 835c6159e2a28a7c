#include "export/map_export.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/log.h"
#include "export/point_cloud_writers.h"

namespace storey {

namespace fs = std::filesystem;

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string storeyStem(int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "storey_%02d", index);
  return name;
}

nlohmann::json optionalNumber(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

nlohmann::json storeyTableJson(const std::vector<StoreyInfo>& storeys) {
  nlohmann::json list = nlohmann::json::array();
  for (const StoreyInfo& s : storeys) {
    nlohmann::json polygon = nlohmann::json::array();
    for (const Eigen::Vector2d& p : s.footprint) polygon.push_back({p.x(), p.y()});
    const std::string stem = storeyStem(s.index);
    list.push_back({{"index", s.index},
                    {"floor_elevation", s.floor_elevation},
                    {"ceiling_elevation", optionalNumber(s.ceiling_elevation)},
                    {"clear_height", optionalNumber(s.clear_height)},
                    {"height", optionalNumber(s.height)},
                    {"area", s.footprint_area},
                    {"floor_area_detected", s.floor_area_detected},
                    {"points", s.points},
                    {"stair_points", s.stair_points},
                    {"files", {"storeys/" + stem + ".las", "storeys/" + stem + ".ply"}},
                    {"footprint", polygon}});
  }
  return list;
}

}  // namespace

std::string storeysJson(const std::vector<StoreyInfo>& storeys, double map_voxel_size) {
  nlohmann::json root;
  root["format"] = "storey-storeys";
  root["version"] = 1;
  root["frame"] = "world: gravity-aligned, z up, origin at the LiDAR's start; metres";
  root["map_voxel_size_m"] = map_voxel_size;
  root["storeys"] = storeyTableJson(storeys);
  return root.dump(2) + "\n";
}

std::vector<std::string> exportMap(const MapCloud& map, const StoreySegmentation& segmentation,
                                   double map_voxel_size, const std::string& out_dir,
                                   const ProgressFn& progress) {
  const fs::path out(out_dir);
  const fs::path storeys_dir = out / "storeys";
  std::error_code ec;
  fs::create_directories(storeys_dir, ec);
  if (ec) throw Error(storeys_dir.string() + ": cannot create the folder: " + ec.message());
  std::vector<std::string> files;
  const std::size_t steps = 3 + 2 * segmentation.storeys.size() + 1;
  std::size_t step = 0;
  auto done = [&](const std::string& file) {
    files.push_back(file);
    if (progress && !progress(static_cast<double>(++step) / static_cast<double>(steps), "export"))
      throw Cancelled();
  };
  writeLas((out / "map.las").string(), map);
  done("map.las");
  writePly((out / "map.ply").string(), map);
  done("map.ply");
  writePcd((out / "map.pcd").string(), map);
  done("map.pcd");

  std::vector<std::vector<std::uint32_t>> members(segmentation.storeys.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    const std::int16_t s = map.storey[i];
    if (s >= 0 && static_cast<std::size_t>(s) < members.size())
      members[static_cast<std::size_t>(s)].push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<std::string> kept;
  for (std::size_t k = 0; k < segmentation.storeys.size(); ++k) {
    const std::string stem = storeyStem(segmentation.storeys[k].index);
    writeLas((storeys_dir / (stem + ".las")).string(), map, &members[k]);
    done("storeys/" + stem + ".las");
    writePly((storeys_dir / (stem + ".ply")).string(), map, &members[k]);
    done("storeys/" + stem + ".ply");
    kept.push_back(stem + ".las");
    kept.push_back(stem + ".ply");
    std::vector<std::uint32_t>().swap(members[k]);
  }
  // Files of a previous run with more storeys would be mistaken for this run's.
  const std::regex stale("storey_[0-9]+\\.(las|ply)");
  for (const auto& entry : fs::directory_iterator(storeys_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, stale) &&
        std::find(kept.begin(), kept.end(), name) == kept.end())
      fs::remove(entry.path(), ec);
  }
  writeFileAtomically((out / "storeys.json").string(),
                      storeysJson(segmentation.storeys, map_voxel_size));
  done("storeys.json");
  return files;
}

MapOutputs buildAndExportMap(const MapBuilder& builder,
                             const std::vector<Pose>& T_world_lidar_per_scan,
                             const std::vector<Eigen::Vector3d>& sensor_position_per_label,
                             const StoreysConfig& storeys_config, const std::string& out_dir,
                             const ProgressFn& progress) {
  validateStoreysConfig(storeys_config);
  MapOutputs outputs;
  auto t0 = std::chrono::steady_clock::now();
  MapCloud map = builder.build(T_world_lidar_per_scan, progress);
  outputs.seconds_build = secondsSince(t0);
  outputs.build = builder.stats();
  outputs.map_points = map.size();
  outputs.map_voxel_size = builder.config().voxel_size;
  logInfo("map: " + std::to_string(map.size()) + " points from " +
          std::to_string(outputs.build.keyframes) + " scans");

  t0 = std::chrono::steady_clock::now();
  StoreySegmentation segmentation;
  if (storeys_config.enabled) {
    segmentation = segmentStoreys(map, sensor_position_per_label, storeys_config, progress);
    if (segmentation.storeys.empty())
      logWarning("storeys: no floor slab of at least " +
                 std::to_string(storeys_config.min_floor_area) + " m^2 found; no storeys");
  } else {
    logInfo("storeys: segmentation switched off (storeys.enabled: false)");
  }
  outputs.seconds_storeys = secondsSince(t0);
  outputs.storeys = segmentation.storeys;
  outputs.segmentation = segmentation.stats;
  for (const StoreyInfo& s : segmentation.storeys) {
    char line[160];
    std::snprintf(line, sizeof(line), "storey %d: floor %.3f m, footprint %.1f m^2, %zu points",
                  s.index, s.floor_elevation, s.footprint_area, s.points);
    logInfo(line);
  }

  t0 = std::chrono::steady_clock::now();
  outputs.files = exportMap(map, segmentation, outputs.map_voxel_size, out_dir, progress);
  outputs.seconds_export = secondsSince(t0);
  outputs.map = std::make_shared<MapCloud>(std::move(map));
  return outputs;
}

std::string addMapToReport(const std::string& report_json, const MapOutputs& o) {
  nlohmann::json report = report_json.empty() ? nlohmann::json::object()
                                              : nlohmann::json::parse(report_json, nullptr, false);
  if (!report.is_object()) throw Error("addMapToReport: the run report is not a JSON object");
  const StoreySegmentationStats& s = o.segmentation;
  report["map"] = {
      {"points", o.map_points},
      {"voxel_size_m", o.map_voxel_size},
      {"keyframes", o.build.keyframes},
      {"keyframe_points", o.build.points_in},
      {"keyframe_points_stored", o.build.points_stored},
      {"left_out", {{"beyond_range", o.build.points_beyond_range},
                    {"non_finite", o.build.points_non_finite}}},
      {"segmentation",
       {{"subsampled_points", s.subsampled_points},
        {"planar_regions", s.regions},
        {"floor_candidates", s.floor_candidates},
        {"ceiling_candidates", s.ceiling_candidates},
        {"floor_slabs", s.floor_slabs},
        {"slabs_rejected", {{"smaller_than_min_floor_area", s.slabs_too_small},
                            {"within_min_storey_height_of_a_larger_floor", s.slabs_too_close}}},
        {"stair_cells", s.stair_cells}}},
      {"files", o.files},
      {"seconds", {{"build", o.seconds_build},
                   {"storeys", o.seconds_storeys},
                   {"normals", s.seconds_normals},
                   {"regions", s.seconds_regions},
                   {"footprints", s.seconds_footprints},
                   {"export", o.seconds_export}}}};
  nlohmann::json table = storeyTableJson(o.storeys);
  for (nlohmann::json& entry : table) entry.erase("footprint");  // in storeys.json
  report["storeys"] = table;
  return report.dump(2);
}

}  // namespace storey
