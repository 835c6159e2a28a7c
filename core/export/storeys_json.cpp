#include "export/storeys_json.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/error.h"
#include "export/storey_files.h"

namespace storey {

namespace {

using Json = nlohmann::json;

Json optionalNumber(const std::optional<double>& v) {
  return v ? Json(*v) : Json(nullptr);
}

std::optional<double> numberOrNone(const Json& j, const char* key) {
  if (!j.contains(key) || !j[key].is_number()) return std::nullopt;
  return j[key].get<double>();
}

/// A count (points): absent is 0; negative, fractional or beyond 2^53 is an error.
std::size_t countOrZero(const Json& j, const char* key, const std::string& where) {
  const double v = numberOrNone(j, key).value_or(0.0);
  if (!(v >= 0.0 && v <= 9007199254740992.0 && v == std::floor(v)))
    throw Error(where + ": '" + key + "' must be a whole number >= 0");
  return static_cast<std::size_t>(v);
}

}  // namespace

Json storeyTableJson(const std::vector<StoreyInfo>& storeys) {
  Json list = Json::array();
  for (const StoreyInfo& s : storeys) {
    Json polygon = Json::array();
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

std::string storeysJson(const std::vector<StoreyInfo>& storeys, double map_voxel_size) {
  Json root;
  root["format"] = "storey-storeys";
  root["version"] = 1;
  root["frame"] = "world: gravity-aligned, z up, origin at the LiDAR's start; metres";
  root["map_voxel_size_m"] = map_voxel_size;
  root["storeys"] = storeyTableJson(storeys);
  return root.dump(2) + "\n";
}

std::vector<StoreyInfo> parseStoreysJson(const std::string& json_text, const std::string& source) {
  Json root;
  try {
    root = Json::parse(json_text);
  } catch (const Json::parse_error& e) {
    throw Error(source + ": not valid JSON (byte " + std::to_string(e.byte) + ")");
  } catch (const Json::exception& e) {  // e.g. out_of_range: a number beyond a double (1e400)
    throw Error(source + ": not valid JSON (" + e.what() + ")");
  }
  const Json* list = &root;
  if (root.is_object()) {
    if (!root.contains("storeys")) throw Error(source + ": expected a 'storeys' array");
    list = &root["storeys"];
  }
  if (!list->is_array()) throw Error(source + ": 'storeys' is not an array");
  std::vector<StoreyInfo> storeys;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const Json& entry = (*list)[i];
    const std::string where = source + ": storeys[" + std::to_string(i) + "]";
    if (!entry.is_object() || !entry.contains("index") || !entry.contains("floor_elevation"))
      throw Error(where + ": needs 'index' and 'floor_elevation'");
    if (!entry["index"].is_number_integer() || !entry["floor_elevation"].is_number())
      throw Error(where + ": 'index' must be an integer and 'floor_elevation' a number");
    StoreyInfo s;
    s.index = entry["index"].get<int>();
    s.floor_elevation = entry["floor_elevation"].get<double>();
    s.ceiling_elevation = numberOrNone(entry, "ceiling_elevation");
    s.clear_height = numberOrNone(entry, "clear_height");
    s.height = numberOrNone(entry, "height");
    s.footprint_area = numberOrNone(entry, "area").value_or(0.0);
    s.floor_area_detected = numberOrNone(entry, "floor_area_detected").value_or(0.0);
    s.points = countOrZero(entry, "points", where);
    s.stair_points = countOrZero(entry, "stair_points", where);
    if (entry.contains("footprint") && entry["footprint"].is_array()) {
      for (const Json& p : entry["footprint"])
        if (p.is_array() && p.size() >= 2 && p[0].is_number() && p[1].is_number())
          s.footprint.emplace_back(p[0].get<double>(), p[1].get<double>());
    }
    storeys.push_back(std::move(s));
  }
  return storeys;
}

std::vector<StoreyInfo> readStoreysJson(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open storeys file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseStoreysJson(text.str(), path);
}

}  // namespace storey
