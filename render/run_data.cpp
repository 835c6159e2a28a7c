// Readers of a run's JSON files and the folder as a whole.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/error.h"
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

Eigen::Vector3d vec3(const Json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw Error(where + ": expected [x, y, z]");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

double number(const Json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_number())
    throw Error(where + ": '" + key + "' missing or not a number");
  return j[key].get<double>();
}

}  // namespace

std::vector<SrpPlane> readPlanesJson(const std::string& path) {
  const Json doc = readJson(path);
  if (!doc.contains("planes") || !doc["planes"].is_array())
    throw Error(path + ": no 'planes' array");
  std::vector<SrpPlane> planes;
  for (std::size_t i = 0; i < doc["planes"].size(); ++i) {
    const Json& p = doc["planes"][i];
    const std::string where = path + ": planes[" + std::to_string(i) + "]";
    SrpPlane plane;
    plane.id =
        p.contains("id") && p["id"].is_number_integer() ? p["id"].get<int>() : static_cast<int>(i);
    plane.normal = vec3(p.value("normal", Json()), where + ".normal");
    plane.distance = number(p, "distance", where);
    plane.facing = p.contains("facing") ? vec3(p["facing"], where + ".facing")
                                        : Eigen::Vector3d(-plane.normal);
    if (p.contains("observations") && p["observations"].is_array()) {
      for (std::size_t k = 0; k < p["observations"].size(); ++k) {
        const Json& o = p["observations"][k];
        const std::string ow = where + ".observations[" + std::to_string(k) + "]";
        SrpObservation obs;
        obs.keyframe = static_cast<int>(number(o, "keyframe", ow));
        obs.normal_lidar = vec3(o.value("normal", Json()), ow + ".normal");
        obs.distance_lidar = number(o, "distance", ow);
        obs.points = o.contains("points") && o["points"].is_number() ? o["points"].get<int>() : 0;
        obs.fit_rms = o.contains("fit_rms_m") && o["fit_rms_m"].is_number()
                          ? o["fit_rms_m"].get<double>()
                          : 0.0;
        obs.outlier =
            o.contains("outlier") && o["outlier"].is_boolean() && o["outlier"].get<bool>();
        if (o.contains("centroid") && !o["centroid"].is_null())
          obs.centroid_lidar = vec3(o["centroid"], ow + ".centroid");
        if (o.contains("hull") && o["hull"].is_array()) {
          for (std::size_t h = 0; h < o["hull"].size(); ++h)
            obs.hull_lidar.push_back(vec3(o["hull"][h], ow + ".hull[" + std::to_string(h) + "]"));
        }
        plane.observations.push_back(std::move(obs));
      }
    }
    planes.push_back(std::move(plane));
  }
  return planes;
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
    run.planes = readPlanesJson((d / "planes.json").string());
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
