#include "export/planes_json.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"

namespace storey {

namespace {

using Json = nlohmann::json;

constexpr const char* kFormat = "storey planes, version 1";

Json vec(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

Json observationJson(const PlaneObservation& o) {
  Json hull = Json::array();
  for (const Eigen::Vector3d& v : o.hull_keyframe) hull.push_back(vec(v));
  Json j = {{"keyframe", o.keyframe},
            {"normal", vec(o.normal_keyframe)},
            {"distance", o.distance_keyframe},
            {"hull", hull},
            {"points", o.points},
            {"fit_rms_m", o.fit_rms},
            {"residual_chi2", o.residual_chi2},
            {"outlier", o.outlier}};
  if (o.time) j["time"] = *o.time;
  if (o.centroid_keyframe) j["centroid"] = vec(*o.centroid_keyframe);
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

std::string planesJsonText(const PlaneMap& map) {
  Json planes = Json::array();
  for (const GlobalPlane& plane : map.planes) {
    Json observations = Json::array();
    for (const PlaneObservation& o : plane.observations) observations.push_back(observationJson(o));
    Json p = {{"id", plane.id},
              {"normal", vec(plane.normal_world)},
              {"distance", plane.distance_world},
              {"observation_count", plane.observations.size()},
              {"observations", observations}};
    if (plane.facing_world) p["facing"] = vec(*plane.facing_world);
    planes.push_back(std::move(p));
  }
  const Json doc = {
      {"format", kFormat},
      {"frame", "world (z up, origin at the LiDAR's start)"},
      {"convention",
       "Hesse normal form n . x = d, |n| = 1, d >= 0, metres; `facing` points from the plane to "
       "the side it was seen from; observations are in the keyframe's LiDAR frame (keyframe = "
       "index into keyframes.tum; centroid of the inliers; hull = their convex outline on the "
       "plane, counter-clockwise seen from the normal's side), residual_chi2 is the whitened "
       "squared residual after the final optimisation (3 dof)"},
      {"keyframes", map.keyframes},
      {"planes", planes}};
  return doc.dump(1);
}

void writePlanesJson(const std::string& path, const PlaneMap& planes) {
  writeFileAtomically(path, planesJsonText(planes) + "\n");
}

PlaneMap parsePlanesJson(const std::string& json_text, const std::string& source) {
  const Json doc = Json::parse(json_text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) throw Error(source + ": not a JSON object");
  if (!doc.contains("planes") || !doc["planes"].is_array())
    throw Error(source + ": no 'planes' array (not a planes.json of storey run)");
  PlaneMap map;
  if (doc.contains("keyframes") && doc["keyframes"].is_number_integer())
    map.keyframes = doc["keyframes"].get<long>();
  const Json& planes = doc["planes"];
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const Json& p = planes[i];
    const std::string where = source + ": planes[" + std::to_string(i) + "]";
    if (!p.is_object()) throw Error(where + ": not an object");
    GlobalPlane plane;
    plane.id =
        p.contains("id") && p["id"].is_number_integer() ? p["id"].get<int>() : static_cast<int>(i);
    plane.normal_world = vec3(p.value("normal", Json()), where + ".normal");
    plane.distance_world = number(p, "distance", where);
    if (p.contains("facing") && !p["facing"].is_null())
      plane.facing_world = vec3(p["facing"], where + ".facing");
    if (p.contains("observations") && p["observations"].is_array()) {
      const Json& observations = p["observations"];
      for (std::size_t k = 0; k < observations.size(); ++k) {
        const Json& o = observations[k];
        const std::string ow = where + ".observations[" + std::to_string(k) + "]";
        if (!o.is_object()) throw Error(ow + ": not an object");
        PlaneObservation obs;
        if (!o.contains("keyframe") || !o["keyframe"].is_number_integer())
          throw Error(ow + ": 'keyframe' missing or not an integer");
        obs.keyframe = o["keyframe"].get<int>();
        if (o.contains("time")) obs.time = number(o, "time", ow);
        obs.normal_keyframe = vec3(o.value("normal", Json()), ow + ".normal");
        obs.distance_keyframe = number(o, "distance", ow);
        if (o.contains("centroid") && !o["centroid"].is_null())
          obs.centroid_keyframe = vec3(o["centroid"], ow + ".centroid");
        if (o.contains("hull") && o["hull"].is_array()) {
          for (std::size_t h = 0; h < o["hull"].size(); ++h)
            obs.hull_keyframe.push_back(
                vec3(o["hull"][h], ow + ".hull[" + std::to_string(h) + "]"));
        }
        if (o.contains("points")) {
          const double points = number(o, "points", ow);
          if (!(points >= 0.0 && points <= 9007199254740992.0 && points == std::floor(points)))
            throw Error(ow + ": 'points' must be a whole number >= 0");
          obs.points = static_cast<long>(points);
        }
        if (o.contains("fit_rms_m")) obs.fit_rms = number(o, "fit_rms_m", ow);
        if (o.contains("residual_chi2")) obs.residual_chi2 = number(o, "residual_chi2", ow);
        if (o.contains("outlier")) {
          if (!o["outlier"].is_boolean()) throw Error(ow + ": 'outlier' is not true or false");
          obs.outlier = o["outlier"].get<bool>();
        }
        plane.observations.push_back(std::move(obs));
      }
    }
    map.planes.push_back(std::move(plane));
  }
  return map;
}

PlaneMap readPlanesJson(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the planes file");
  std::ostringstream text;
  text << in.rdbuf();
  return parsePlanesJson(text.str(), path);
}

}  // namespace storey
