// `storey storeys RUN_DIR -o OUT`: the storey stage again on a finished run's
// map (map.ply and keyframes.tum), with the configuration's storeys: section;
// writes the map files, storeys/ and storeys.json into OUT.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "common/error.h"
#include "config/config.h"
#include "eval/ply_reader.h"
#include "export/map_export.h"
#include "progress_bar.h"
#include "storeys/storey_segmentation.h"
#include "trajectory/tum.h"

namespace storey::cli {

namespace {

namespace fs = std::filesystem;

/// The run's map as `storey run` wrote it (the storey labels and flags are
/// recomputed). The keyframe of every point must index keyframes.tum.
MapCloud readRunMap(const std::string& path, std::size_t keyframes) {
  const eval::PlyVertexColumns ply =
      eval::readPlyVertexColumns(path, {"intensity", "time", "keyframe"});
  MapCloud map;
  map.reserve(ply.positions.size());
  for (std::size_t i = 0; i < ply.positions.size(); ++i) {
    const double keyframe = ply.columns[2][i];
    if (!(keyframe >= -1.0 && keyframe < static_cast<double>(keyframes)))
      throw Error(path + ": vertex " + std::to_string(i) + ": keyframe " +
                  std::to_string(keyframe) + " is not one of keyframes.tum's " +
                  std::to_string(keyframes) + " (the map and the keyframes of different runs?)");
    map.positions.push_back(ply.positions[i].cast<float>());
    map.intensity.push_back(static_cast<float>(ply.columns[0][i]));
    map.time.push_back(ply.columns[1][i]);
    map.keyframe.push_back(static_cast<std::int32_t>(keyframe));
    map.storey.push_back(kNoStorey);
    map.flags.push_back(0);
  }
  return map;
}

/// The map voxel size the run's storeys.json records, else `fallback`.
double runVoxelSize(const fs::path& run_dir, double fallback) {
  std::ifstream in(run_dir / "storeys.json");
  if (!in) return fallback;
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json root = nlohmann::json::parse(text.str(), nullptr, false);
  if (root.is_object() && root.contains("map_voxel_size_m") && root["map_voxel_size_m"].is_number())
    return root["map_voxel_size_m"].get<double>();
  return fallback;
}

}  // namespace

int runStoreys(const StoreysOptions& options) {
  Config config = options.config_path.empty() ? Config{} : loadConfig(options.config_path);
  config.validate();
  if (!config.storeys.enabled)
    throw Error(
        (options.config_path.empty() ? std::string("the configuration") : options.config_path) +
        ": storeys.enabled is false: there is nothing to split");
  const fs::path run_dir(options.run_dir);
  std::error_code ec;
  if (fs::exists(options.out_dir, ec) && fs::equivalent(run_dir, options.out_dir, ec))
    throw Error(options.out_dir +
                ": the run folder itself (its report describes the storeys it found): write the "
                "new split into another folder");
  const Trajectory keyframes = readTum((run_dir / "keyframes.tum").string());
  std::vector<Eigen::Vector3d> keyframe_positions;
  keyframe_positions.reserve(keyframes.size());
  for (const StampedPose& k : keyframes) keyframe_positions.push_back(k.pose.translation());

  ProgressBar bar("storeys");
  MapCloud map = readRunMap((run_dir / "map.ply").string(), keyframes.size());
  const StoreySegmentation segmentation =
      segmentStoreys(map, keyframe_positions, config.storeys, bar.callback());
  fs::create_directories(options.out_dir);
  const std::vector<std::string> files = writeMapFiles(options.out_dir, map, segmentation,
                                                       runVoxelSize(run_dir, config.map.voxel_size),
                                                       bar.callback(), config.map.export_threads);
  bar.done();

  const StoreySegmentationStats& stats = segmentation.stats;
  char counts[200];
  std::snprintf(counts, sizeof(counts),
                " (%zu floor slabs; %zu stair flight ends, %zu of them on a floor; the sensor "
                "%.2f m above the floor)\n",
                stats.floor_slabs, stats.flight_ends, stats.flight_ends_on_floor,
                stats.usual_sensor_height);
  std::cout << "storey storeys: " << segmentation.storeys.size() << " storeys in " << map.size()
            << " map points" << counts;
  for (const StoreyInfo& s : segmentation.storeys) {
    char line[160];
    std::snprintf(line, sizeof(line), "  storey %d: floor %.3f m, footprint %.1f m^2, %zu points\n",
                  s.index, s.floor_elevation, s.footprint_area, s.points);
    std::cout << line;
  }
  std::cout << files.size() << " files in " << options.out_dir << '\n';
  return 0;
}

}  // namespace storey::cli
