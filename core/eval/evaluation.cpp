#include "eval/evaluation.h"

#include <chrono>
#include <cmath>

#include "common/error.h"
#include "eval/mesh_distance.h"
#include "eval/ply_reader.h"

namespace storey::eval {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void EvaluationConfig::validate() const {
  association.validate();
  if (rpe_segment_lengths.empty()) throw Error("eval: rpe_segment_lengths is empty");
  for (double length : rpe_segment_lengths)
    if (!(length > 0.0) || !std::isfinite(length))
      throw Error("eval: every RPE segment length must be > 0 m");
  if (rpe_stride < 1) throw Error("eval: rpe_stride must be >= 1");
  if (!(map_within_distance > 0.0)) throw Error("eval: map_within_distance must be > 0 m");
  if (!(storey_match_gate > 0.0)) throw Error("eval: storey_match_gate must be > 0 m");
  if (threads < 0) throw Error("eval: threads must be >= 0");
}

const AteResult& TrajectoryEvaluation::ateWith(Alignment alignment) const {
  for (const AteResult& a : ate)
    if (a.alignment == alignment) return a;
  throw Error(std::string("eval: no ATE with alignment ") + toString(alignment));
}

TrajectoryEvaluation evaluateTrajectory(const Trajectory& gt, const Trajectory& est,
                                        const EvaluationConfig& config) {
  config.validate();
  const AssociatedPoses poses = associate(gt, est, config.association);
  TrajectoryEvaluation result;
  result.gt_poses = gt.size();
  result.est_poses = est.size();
  result.matched = poses.matched();
  result.outside_gt_span = poses.outside_gt_span;
  result.in_gt_gap = poses.in_gt_gap;
  result.matched_duration = poses.times.back() - poses.times.front();
  for (std::size_t i = 1; i < poses.matched(); ++i)
    result.gt_path_length +=
        (poses.T_world_gt[i].translation() - poses.T_world_gt[i - 1].translation()).norm();
  for (Alignment alignment : {Alignment::kNone, Alignment::kSe3, Alignment::kYawTranslation})
    result.ate.push_back(absoluteTrajectoryError(poses, alignment));
  for (double length : config.rpe_segment_lengths)
    result.rpe.push_back(relativePoseError(poses, length, config.rpe_stride));
  result.est_drift = endPointDrift(est);
  result.gt_drift = endPointDrift(gt);
  return result;
}

MapEvaluation evaluateMap(const std::string& mesh_path, const std::string& map_path,
                          const EvaluationConfig& config) {
  config.validate();
  MapEvaluation result;
  result.within_distance = config.map_within_distance;
  auto start = std::chrono::steady_clock::now();
  const PlyMesh mesh = readPlyMesh(mesh_path, config.mesh_returning_faces_only);
  const PlyPoints map = readPlyPoints(map_path);
  result.read_seconds = secondsSince(start);
  result.points = map.positions.size();
  result.non_finite_points = map.non_finite;
  result.faces_not_returning = mesh.faces_not_returning;
  if (map.positions.empty()) throw Error(map_path + ": the map has no finite point");

  start = std::chrono::steady_clock::now();
  std::optional<MeshDistance> distance;
  try {
    distance.emplace(mesh.vertices, mesh.triangles);
  } catch (const Error& e) {
    throw Error(mesh_path + ": " + e.what());
  }
  result.triangles = distance->triangles();
  result.build_seconds = secondsSince(start);

  start = std::chrono::steady_clock::now();
  std::vector<double> d = distance->distances(map.positions, config.threads);
  result.query_seconds = secondsSince(start);
  std::size_t within = 0;
  for (double x : d)
    if (x <= config.map_within_distance) ++within;
  result.fraction_within = static_cast<double>(within) / static_cast<double>(d.size());
  result.distance = errorStats(std::move(d));
  return result;
}

EvaluationResult evaluate(const EvaluationInputs& inputs, const EvaluationConfig& config) {
  config.validate();
  if (inputs.gt_path.empty()) throw Error("eval: no ground-truth trajectory given");
  if (inputs.est_path.empty()) throw Error("eval: no estimated trajectory given");
  EvaluationResult result;
  result.inputs = inputs;

  const Trajectory gt = readTum(inputs.gt_path);
  const Trajectory est = readTum(inputs.est_path);
  try {
    result.trajectory = evaluateTrajectory(gt, est, config);
  } catch (const Error& e) {
    throw Error(inputs.est_path + " against " + inputs.gt_path + ": " + e.what());
  }

  if (inputs.true_storeys_path.empty()) {
    result.notes.push_back("storeys: skipped (no true storeys file given)");
  } else if (inputs.estimated_storeys_path.empty()) {
    result.notes.push_back("storeys: skipped (no estimated storeys.json given or found)");
  } else {
    result.storeys = compareStoreys(readTrueStoreys(inputs.true_storeys_path),
                                    readEstimatedStoreys(inputs.estimated_storeys_path),
                                    config.storey_match_gate);
  }

  if (inputs.mesh_path.empty() && inputs.map_path.empty()) {
    result.notes.push_back("map: skipped (no mesh and map given)");
  } else if (inputs.mesh_path.empty() || inputs.map_path.empty()) {
    throw Error(std::string("eval: the map-to-mesh distance needs both a mesh and a map (") +
                (inputs.mesh_path.empty() ? "no mesh given" : "no map given") + ")");
  } else {
    result.map = evaluateMap(inputs.mesh_path, inputs.map_path, config);
  }
  if (inputs.planes_path.empty()) {
    result.notes.push_back("planes: skipped (no planes.json given)");
  } else {
    PlaneCheckOptions options = config.plane_check;
    options.max_time_difference = config.association.max_time_difference;
    result.planes = checkPlanes(inputs.planes_path, gt, options);
  }
  return result;
}

}  // namespace storey::eval
