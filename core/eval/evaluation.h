#pragma once
/// `storey eval`: an estimated trajectory (and optionally its map and storeys)
/// against ground truth. ATE without alignment, with SE(3) and with yaw +
/// translation alignment; RPE over path segments; the end-point drift table
/// (the paper's Table I) of estimate and truth; per-storey floor elevation
/// error; map-to-mesh distance. Each part is a function on in-memory data (the
/// run report reuses them) and evaluate() reads the files and runs them all.
#include <optional>
#include <string>
#include <vector>

#include "eval/association.h"
#include "eval/ate.h"
#include "eval/error_stats.h"
#include "eval/plane_check.h"
#include "eval/rpe.h"
#include "eval/storey_error.h"
#include "trajectory/drift.h"

namespace storey::eval {

struct EvaluationConfig {
  AssociationOptions association;
  std::vector<double> rpe_segment_lengths{10.0};  ///< RPE path segment lengths [m, > 0]
  int rpe_stride = 1;                     ///< RPE: a segment starts at every n-th stamp [>= 1]
  double map_within_distance = 0.05;      ///< map points this close to the mesh count as good [m]
  bool mesh_returning_faces_only = true;  ///< leave out faces with `returns` 0 (glass)
  double storey_match_gate = 1.0;         ///< largest floor elevation difference matched [m]
  int threads = 0;                        ///< map distance threads; 0 = all cores
  PlaneCheckOptions plane_check;
  void validate() const;  ///< storey::Error naming the bad field
};

struct EvaluationInputs {
  std::string gt_path;                 ///< true trajectory, TUM (required)
  std::string est_path;                ///< estimated trajectory, TUM (required)
  std::string mesh_path;               ///< true mesh, PLY (with map_path)
  std::string map_path;                ///< map point cloud, PLY (with mesh_path)
  std::string true_storeys_path;       ///< storeys.yaml of the simulator
  std::string estimated_storeys_path;  ///< storeys.json of `storey run`
  std::string planes_path;             ///< planes.json of `storey run`: associations checked
};

struct TrajectoryEvaluation {
  std::size_t gt_poses = 0, est_poses = 0;
  std::size_t matched = 0, outside_gt_span = 0, in_gt_gap = 0;  ///< association counts
  double matched_duration = 0.0;                                ///< first to last matched stamp [s]
  double gt_path_length = 0.0;  ///< true path length over the matched stamps [m]
  std::vector<AteResult> ate;   ///< kNone, kSe3, kYawTranslation, in this order
  std::vector<RpeResult> rpe;   ///< one per segment length
  EndPointDrift est_drift;      ///< the whole estimate
  EndPointDrift gt_drift;       ///< the whole truth (near zero when the walk returns to its start)
  const AteResult& ateWith(Alignment alignment) const;
};

struct MapEvaluation {
  std::size_t points = 0;               ///< finite map points measured
  std::size_t non_finite_points = 0;    ///< left out
  std::size_t triangles = 0;            ///< mesh triangles in the tree
  std::size_t faces_not_returning = 0;  ///< mesh faces left out (glass)
  ErrorStats distance;                  ///< point-to-mesh distance [m]
  double within_distance = 0.05;        ///< [m]
  double fraction_within = 0.0;         ///< of the points, within within_distance [0, 1]
  double read_seconds = 0.0, build_seconds = 0.0, query_seconds = 0.0;  ///< wall time [s]
};

struct EvaluationResult {
  EvaluationInputs inputs;
  TrajectoryEvaluation trajectory;
  std::optional<StoreyComparison> storeys;
  std::optional<MapEvaluation> map;
  std::optional<PlaneCheck> planes;
  std::vector<std::string> notes;  ///< parts skipped and why
};

/// Trajectory part; throws storey::Error when fewer than 2 poses associate.
TrajectoryEvaluation evaluateTrajectory(const Trajectory& gt, const Trajectory& est,
                                        const EvaluationConfig& config = {});
/// Map part from the two PLY files (mesh: triangles; map: vertex x y z).
MapEvaluation evaluateMap(const std::string& mesh_path, const std::string& map_path,
                          const EvaluationConfig& config = {});
/// Everything `inputs` names; parts whose inputs are missing are skipped with a note.
EvaluationResult evaluate(const EvaluationInputs& inputs, const EvaluationConfig& config = {});

}  // namespace storey::eval
