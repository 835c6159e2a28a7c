// Readers of a run's JSON files and the folder as a whole.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "export/planes_json.h"
#include "export/storeys_json.h"
#include "render/run_data.h"

namespace storey::render {

Eigen::Vector3d facingOf(const GlobalPlane& plane) {
  return plane.facing_world ? *plane.facing_world : Eigen::Vector3d(-plane.normal_world);
}

std::vector<StoreyEntry> readStoreysJson(const std::string& path) {
  std::vector<StoreyEntry> out;
  for (const StoreyInfo& s : storey::readStoreysJson(path))
    out.push_back({s.index, s.floor_elevation, s.ceiling_elevation, s.height, s.footprint_area,
                   s.points, s.footprint});
  std::sort(out.begin(), out.end(),
            [](const StoreyEntry& a, const StoreyEntry& b) { return a.floor < b.floor; });
  return out;
}

int storeyOfElevation(const std::vector<StoreyEntry>& storeys, double z, double tolerance) {
  if (storeys.empty()) return -1;
  int result = storeys.front().index;
  for (const StoreyEntry& s : storeys)
    if (z >= s.floor - tolerance) result = s.index;
  return result;
}

RunData loadRun(const std::string& dir, std::size_t max_points, const MapSample* map_sample) {
  namespace fs = std::filesystem;
  RunData run;
  run.dir = dir;
  if (!fs::is_directory(dir))
    throw Error(dir + ": not a folder (expected the output folder of storey run)");
  const fs::path d(dir);
  const fs::path trajectory = d / "trajectory.tum";
  if (!fs::exists(trajectory))
    throw Error(dir + ": no trajectory.tum: not the output folder of a finished storey run");
  run.trajectory = readTum(trajectory.string());
  if (fs::exists(d / "keyframes.tum"))
    run.keyframes = readTum((d / "keyframes.tum").string());
  else
    run.notes.push_back("no keyframes.tum (run without the SRP back end): no SRP views");
  if (fs::exists(d / "planes.json"))
    run.planes = readPlanesJson((d / "planes.json").string()).planes;
  else
    run.notes.push_back("no planes.json: no SRP patches");
  if (fs::exists(d / "storeys.json"))
    run.storeys = readStoreysJson((d / "storeys.json").string());
  else
    run.notes.push_back("no storeys.json: the map is shown as one storey");
  if (map_sample != nullptr)
    run.map = *map_sample;
  else if (fs::exists(d / "map.ply"))
    run.map = readMapSample((d / "map.ply").string(), max_points);
  else
    run.notes.push_back("no map.ply: the trajectory is drawn without the map");
  return run;
}

}  // namespace storey::render
