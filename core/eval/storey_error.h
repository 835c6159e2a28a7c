#pragma once
/// Floor elevation error of each storey: the true storeys (the simulator's
/// storeys.yaml) against the estimated ones (storeys.json of `storey run`).
///
/// storeys.yaml (truth):   storeys: [{index: 0, floor_z: 0.0, ceiling_z: 2.8}, ...]
/// storeys.json (estimate): {"storeys": [{"index": 0, "floor_elevation": 0.01, ...}, ...]}
///   (a top-level array of the same objects is accepted too; other fields are ignored).
#include <optional>
#include <string>
#include <vector>

namespace storey::eval {

struct StoreyLevel {
  int index = 0;
  double floor_elevation = 0.0;  ///< top of the floor slab, world z [m]
};

/// Throws storey::Error naming the file and the entry for a missing or bad field.
std::vector<StoreyLevel> readTrueStoreys(const std::string& yaml_path);
std::vector<StoreyLevel> readEstimatedStoreys(const std::string& json_path);

struct StoreyMatch {
  int true_index = 0;
  double true_elevation = 0.0;         ///< [m]
  std::optional<int> estimated_index;  ///< none: no estimated floor within the gate
  double estimated_elevation = 0.0;    ///< [m]
  double error = 0.0;                  ///< estimated - true elevation [m]
};

struct StoreyComparison {
  std::size_t true_storeys = 0;
  std::size_t estimated_storeys = 0;
  std::vector<StoreyMatch> storeys;  ///< one per true storey, by true elevation
  std::size_t missed = 0;            ///< true storeys without an estimate
  std::size_t extra = 0;             ///< estimated storeys matched to no true one
  double max_abs_error = 0.0;        ///< over the matched storeys [m]
};

/// Each true storey is matched to the nearest estimated floor elevation within
/// `gate` (each estimate used once, closest pairs first); indices need not agree.
StoreyComparison compareStoreys(const std::vector<StoreyLevel>& truth,
                                const std::vector<StoreyLevel>& estimate, double gate = 1.0);

}  // namespace storey::eval
