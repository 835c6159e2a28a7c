#include "eval/storey_error.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "common/error.h"
#include "export/storeys_json.h"

namespace storey::eval {

std::vector<StoreyLevel> readTrueStoreys(const std::string& yaml_path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path);
  } catch (const YAML::BadFile&) {
    throw Error(yaml_path + ": cannot open storeys file");
  } catch (const YAML::Exception& e) {
    throw Error(yaml_path + ": line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  const YAML::Node list = root["storeys"];
  if (!list || !list.IsSequence()) throw Error(yaml_path + ": expected a 'storeys' list");
  std::vector<StoreyLevel> storeys;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node entry = list[i];
    const std::string where = yaml_path + ": storeys[" + std::to_string(i) + "] (line " +
                              std::to_string(entry.Mark().line + 1) + ")";
    try {
      if (!entry["index"] || !entry["floor_z"])
        throw Error(where + ": needs 'index' and 'floor_z'");
      storeys.push_back({entry["index"].as<int>(), entry["floor_z"].as<double>()});
    } catch (const YAML::Exception&) {
      throw Error(where + ": 'index' must be an integer and 'floor_z' a number");
    }
    if (!std::isfinite(storeys.back().floor_elevation))
      throw Error(where + ": floor_z is not finite");
  }
  return storeys;
}

std::vector<StoreyLevel> readEstimatedStoreys(const std::string& json_path) {
  std::vector<StoreyLevel> storeys;
  for (const StoreyInfo& s : readStoreysJson(json_path))
    storeys.push_back({s.index, s.floor_elevation});
  return storeys;
}

StoreyComparison compareStoreys(const std::vector<StoreyLevel>& truth,
                                const std::vector<StoreyLevel>& estimate, double gate) {
  StoreyComparison result;
  result.true_storeys = truth.size();
  result.estimated_storeys = estimate.size();
  std::vector<StoreyLevel> sorted_truth = truth;
  std::sort(sorted_truth.begin(), sorted_truth.end(),
            [](const StoreyLevel& a, const StoreyLevel& b) {
              return a.floor_elevation < b.floor_elevation;
            });
  // Greedy assignment, closest pairs first.
  struct Pair {
    double distance;
    std::size_t t, e;
  };
  std::vector<Pair> pairs;
  for (std::size_t t = 0; t < sorted_truth.size(); ++t)
    for (std::size_t e = 0; e < estimate.size(); ++e) {
      const double d = std::abs(estimate[e].floor_elevation - sorted_truth[t].floor_elevation);
      if (d <= gate) pairs.push_back({d, t, e});
    }
  std::sort(pairs.begin(), pairs.end(),
            [](const Pair& a, const Pair& b) { return a.distance < b.distance; });
  std::vector<int> truth_to_estimate(sorted_truth.size(), -1);
  std::vector<bool> estimate_used(estimate.size(), false);
  for (const Pair& p : pairs) {
    if (truth_to_estimate[p.t] >= 0 || estimate_used[p.e]) continue;
    truth_to_estimate[p.t] = static_cast<int>(p.e);
    estimate_used[p.e] = true;
  }
  for (std::size_t t = 0; t < sorted_truth.size(); ++t) {
    StoreyMatch match;
    match.true_index = sorted_truth[t].index;
    match.true_elevation = sorted_truth[t].floor_elevation;
    if (truth_to_estimate[t] >= 0) {
      const StoreyLevel& e = estimate[static_cast<std::size_t>(truth_to_estimate[t])];
      match.estimated_index = e.index;
      match.estimated_elevation = e.floor_elevation;
      match.error = e.floor_elevation - match.true_elevation;
      result.max_abs_error = std::max(result.max_abs_error, std::abs(match.error));
    } else {
      ++result.missed;
    }
    result.storeys.push_back(match);
  }
  result.extra =
      static_cast<std::size_t>(std::count(estimate_used.begin(), estimate_used.end(), false));
  return result;
}

}  // namespace storey::eval
