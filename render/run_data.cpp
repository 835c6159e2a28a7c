// Readers of a run's JSON files and the folder as a whole.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/error.h"
#include "export/planes_json.h"
#include "render/run_data.h"

namespace storey::render {
namespace {

using Json = nlohmann::json;

Json readJson(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  std::ostringstream os;
  os << in.rdbuf();
  Json j = Json::parse(os.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw Error(path + ": not a JSON object");
  return j;
}

double number(const Json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_number())
    throw Error(where + ": '" + key + "' missing or not a number");
  return j[key].get<double>();
}

}  // namespace

Eigen::Vector3d facingOf(const GlobalPlane& plane) {
  return plane.facing_world ? *plane.facing_world : Eigen::Vector3d(-plane.normal_world);
}

std::vector<StoreyEntry> readStoreysJson(const std::string& path) {
  const Json doc = readJson(path);
  if (!doc.contains("storeys") || !doc["storeys"].is_array())
    throw Error(path + ": no 'storeys' array");
  std::vector<StoreyEntry> out;
  for (std::size_t i = 0; i < doc["storeys"].size(); ++i) {
    const Json& s = doc["storeys"][i];
    const std::string where = path + ": storeys[" + std::to_string(i) + "]";
    StoreyEntry e;
    e.index = s.contains("index") && s["index"].is_number_integer() ? s["index"].get<int>()
                                                                    : static_cast<int>(i);
    e.floor = number(s, "floor_elevation", where);
    if (s.contains("ceiling_elevation") && s["ceiling_elevation"].is_number())
      e.ceiling = s["ceiling_elevation"].get<double>();
    if (s.contains("height") && s["height"].is_number()) e.height = s["height"].get<double>();
    if (s.contains("area") && s["area"].is_number()) e.area = s["area"].get<double>();
    if (s.contains("points") && s["points"].is_number()) e.points = s["points"].get<std::size_t>();
    if (s.contains("footprint") && s["footprint"].is_array()) {
      for (const Json& p : s["footprint"])
        if (p.is_array() && p.size() >= 2 && p[0].is_number() && p[1].is_number())
          e.footprint.emplace_back(p[0].get<double>(), p[1].get<double>());
    }
    out.push_back(std::move(e));
  }
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

RunData loadRun(const std::string& dir, std::size_t max_points) {
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
  if (fs::exists(d / "map.ply"))
    run.map = readMapSample((d / "map.ply").string(), max_points);
  else
    run.notes.push_back("no map.ply: the trajectory is drawn without the map");
  return run;
}

}  // namespace storey::render
