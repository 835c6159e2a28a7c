#include "eval/eval_report.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"

namespace storey::eval {
namespace {

using nlohmann::json;

constexpr double kDegPerRad = 180.0 / M_PI;

json statsJson(const ErrorStats& s, double scale = 1.0) {
  return {{"count", s.count},           {"rmse", s.rmse * scale}, {"mean", s.mean * scale},
          {"median", s.median * scale}, {"p95", s.p95 * scale},   {"max", s.max * scale}};
}

json poseJson(const Pose& T) {
  const Eigen::Vector3d& t = T.translation();
  const Eigen::Quaterniond& q = T.rotation();
  return {{"translation", {t.x(), t.y(), t.z()}}, {"rotation_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

json driftJson(const EndPointDrift& d) {
  return {{"dx_m", d.dx},
          {"dy_m", d.dy},
          {"dz_m", d.dz},
          {"dxyz_m", d.dxyz},
          {"dyaw_rad", d.dyaw},
          {"dpitch_rad", d.dpitch},
          {"droll_rad", d.droll},
          {"dangle_rad", d.dangle},
          {"path_length_m", d.path_length},
          {"dxyz_percent_of_path", d.percent_of_path()}};
}

json pathOrNull(const std::string& path) {
  return path.empty() ? json(nullptr) : json(path);
}

/// printf into a std::string.
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buffer[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof(buffer), fmt, args);
  va_end(args);
  return buffer;
}

}  // namespace

std::string evaluationJson(const EvaluationResult& result) {
  const TrajectoryEvaluation& t = result.trajectory;
  json root;
  root["format"] = "storey-eval";
  root["version"] = 1;
  root["inputs"] = {{"gt", pathOrNull(result.inputs.gt_path)},
                    {"est", pathOrNull(result.inputs.est_path)},
                    {"mesh", pathOrNull(result.inputs.mesh_path)},
                    {"map", pathOrNull(result.inputs.map_path)},
                    {"true_storeys", pathOrNull(result.inputs.true_storeys_path)},
                    {"estimated_storeys", pathOrNull(result.inputs.estimated_storeys_path)},
                    {"planes", pathOrNull(result.inputs.planes_path)}};
  root["association"] = {{"gt_poses", t.gt_poses},
                         {"est_poses", t.est_poses},
                         {"matched", t.matched},
                         {"outside_gt_span", t.outside_gt_span},
                         {"in_gt_gap", t.in_gt_gap},
                         {"matched_duration_s", t.matched_duration},
                         {"gt_path_length_m", t.gt_path_length}};
  json ate = json::array();
  for (const AteResult& a : t.ate)
    ate.push_back({{"alignment", toString(a.alignment)},
                   {"translation_m", statsJson(a.translation)},
                   {"rotation_rad", statsJson(a.rotation)},
                   {"vertical_m", statsJson(a.vertical)},
                   {"tilt_rad", statsJson(a.tilt)},
                   {"T_gt_est", poseJson(a.T_gt_est)}});
  root["ate"] = ate;
  json rpe = json::array();
  for (const RpeResult& r : t.rpe)
    rpe.push_back({{"segment_length_m", r.segment_length},
                   {"segments", r.translation_percent.count},
                   {"translation_percent", statsJson(r.translation_percent)},
                   {"rotation_rad_per_m", statsJson(r.rotation_per_metre)},
                   {"rotation_deg_per_m", statsJson(r.rotation_per_metre, kDegPerRad)}});
  root["rpe"] = rpe;
  root["drift"] = {{"estimate", driftJson(t.est_drift)}, {"ground_truth", driftJson(t.gt_drift)}};

  if (result.storeys) {
    const StoreyComparison& s = *result.storeys;
    json storeys = json::array();
    for (const StoreyMatch& m : s.storeys)
      storeys.push_back(
          {{"true_index", m.true_index},
           {"true_floor_elevation_m", m.true_elevation},
           {"estimated_index", m.estimated_index ? json(*m.estimated_index) : json(nullptr)},
           {"estimated_floor_elevation_m",
            m.estimated_index ? json(m.estimated_elevation) : json(nullptr)},
           {"error_m", m.estimated_index ? json(m.error) : json(nullptr)}});
    root["storeys"] = {{"true_storeys", s.true_storeys},
                       {"estimated_storeys", s.estimated_storeys},
                       {"missed", s.missed},
                       {"extra", s.extra},
                       {"max_abs_error_m", s.max_abs_error},
                       {"storeys", storeys}};
  } else {
    root["storeys"] = nullptr;
  }

  if (result.planes) {
    const PlaneCheck& p = *result.planes;
    json wrong = json::array();
    for (const WrongObservation& w : p.wrong)
      wrong.push_back({{"plane", w.plane},
                       {"keyframe", w.keyframe},
                       {"offset_m", w.offset},
                       {"normal_angle_deg", w.angle_deg},
                       {"down_weighted", w.down_weighted}});
    root["planes"] = {{"planes", p.planes},
                      {"observations", p.observations},
                      {"down_weighted", p.down_weighted},
                      {"off_their_plane", p.wrong.size()},
                      {"off_their_plane_not_down_weighted", p.wrongNotDownWeighted()},
                      {"max_offset_m", p.max_offset},
                      {"max_normal_angle_deg", p.max_angle_deg},
                      {"offset_median_m", p.offset_median},
                      {"offset_p90_m", p.offset_p90},
                      {"tight_offset_m", p.tight_offset},
                      {"beyond_tight_offset", p.beyond_tight_offset},
                      {"observations_off_their_plane", wrong}};
  } else {
    root["planes"] = nullptr;
  }

  if (result.map) {
    const MapEvaluation& m = *result.map;
    root["map"] = {
        {"points", m.points},
        {"non_finite_points", m.non_finite_points},
        {"triangles", m.triangles},
        {"faces_not_returning", m.faces_not_returning},
        {"distance_m", statsJson(m.distance)},
        {"within_distance_m", m.within_distance},
        {"fraction_within", m.fraction_within},
        {"seconds",
         {{"read", m.read_seconds}, {"build", m.build_seconds}, {"query", m.query_seconds}}}};
  } else {
    root["map"] = nullptr;
  }
  root["notes"] = result.notes;
  return root.dump(2) + "\n";
}

void writeEvaluationJson(const std::string& path, const EvaluationResult& result) {
  writeFileAtomically(path, evaluationJson(result));
}

std::string evaluationTable(const EvaluationResult& result) {
  const TrajectoryEvaluation& t = result.trajectory;
  std::string out;
  out +=
      "Trajectory: " + result.inputs.est_path + "\nGround truth: " + result.inputs.gt_path + "\n";
  out += format(
      "Matched poses: %zu of %zu (outside the truth's span %zu, in a truth gap %zu); "
      "%.1f s, %.1f m of true path\n\n",
      t.matched, t.est_poses, t.outside_gt_span, t.in_gt_gap, t.matched_duration, t.gt_path_length);

  out += format("%-19s %9s %9s %9s %9s %9s %9s %9s\n", "ATE", "rmse m", "mean m", "median m",
                "max m", "rot deg", "z max m", "tilt mrad");
  for (const AteResult& a : t.ate)
    out += format("  %-17s %9.4f %9.4f %9.4f %9.4f %9.3f %9.4f %9.2f\n", toString(a.alignment),
                  a.translation.rmse, a.translation.mean, a.translation.median, a.translation.max,
                  a.rotation.rmse * kDegPerRad, a.vertical.max, a.tilt.rmse * 1e3);

  out += format("\n%-19s %9s %9s %9s %9s %9s\n", "RPE", "segments", "trans %", "median",
                "rot deg/m", "median");
  for (const RpeResult& r : t.rpe) {
    const std::string name = format("per %.1f m", r.segment_length);
    if (r.translation_percent.count == 0) {
      out +=
          format("  %-17s %9d   (the matched path is shorter than one segment)\n", name.c_str(), 0);
      continue;
    }
    out +=
        format("  %-17s %9zu %9.3f %9.3f %9.5f %9.5f\n", name.c_str(), r.translation_percent.count,
               r.translation_percent.mean, r.translation_percent.median,
               r.rotation_per_metre.mean * kDegPerRad, r.rotation_per_metre.median * kDegPerRad);
  }

  out +=
      format("\n%-19s %8s %8s %8s %8s %8s %8s %8s %8s %8s %7s\n", "End-point drift", "dX m", "dY m",
             "dZ m", "dXYZ m", "dYaw deg", "dPitch", "dRoll", "dAngle", "path m", "% path");
  auto drift_row = [&](const char* name, const EndPointDrift& d) {
    out += format("  %-17s %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f %8.1f %7.2f\n", name,
                  d.dx, d.dy, d.dz, d.dxyz, d.dyaw * kDegPerRad, d.dpitch * kDegPerRad,
                  d.droll * kDegPerRad, d.dangle * kDegPerRad, d.path_length, d.percent_of_path());
  };
  drift_row("estimate", t.est_drift);
  drift_row("ground truth", t.gt_drift);

  if (result.storeys) {
    const StoreyComparison& s = *result.storeys;
    out += format("\nStoreys: %zu true, %zu estimated, %zu missed, %zu extra; max |error| %.3f m\n",
                  s.true_storeys, s.estimated_storeys, s.missed, s.extra, s.max_abs_error);
    out += "  true  floor m   est  floor m    error m\n";
    for (const StoreyMatch& m : s.storeys) {
      if (m.estimated_index)
        out += format("  %4d %8.3f  %4d %8.3f  %+9.3f\n", m.true_index, m.true_elevation,
                      *m.estimated_index, m.estimated_elevation, m.error);
      else
        out += format("  %4d %8.3f     -        -          -\n", m.true_index, m.true_elevation);
    }
  }

  if (result.planes) {
    const PlaneCheck& p = *result.planes;
    out += format(
        "\nPlane associations under the true poses: %zu planes, %zu observations, "
        "%zu down-weighted\n  off their plane (> %.2f m or > %.1f deg): %zu, of them not "
        "down-weighted: %zu\n",
        p.planes, p.observations, p.down_weighted, p.max_offset, p.max_angle_deg, p.wrong.size(),
        p.wrongNotDownWeighted());
    out += format(
        "  offset from their plane: median %.4f m, 90th percentile %.4f m, beyond %.2f m: %zu "
        "(%.1f %%)\n",
        p.offset_median, p.offset_p90, p.tight_offset, p.beyond_tight_offset,
        p.observations ? 100.0 * static_cast<double>(p.beyond_tight_offset) /
                             static_cast<double>(p.observations)
                       : 0.0);
    for (const WrongObservation& w : p.wrong)
      out += format("  plane %d keyframe %d: offset %+.3f m, normal %.1f deg%s\n", w.plane,
                    w.keyframe, w.offset, w.angle_deg, w.down_weighted ? " (down-weighted)" : "");
  }

  if (result.map) {
    const MapEvaluation& m = *result.map;
    out += format("\nMap to mesh (m): %zu points, %zu triangles\n", m.points, m.triangles);
    out += format("  %9s %9s %9s %9s  %s\n", "mean", "median", "p95", "max", "within");
    out +=
        format("  %9.4f %9.4f %9.4f %9.4f  %5.1f%% <= %.3f m\n", m.distance.mean, m.distance.median,
               m.distance.p95, m.distance.max, 100.0 * m.fraction_within, m.within_distance);
    out += format("  time: read %.2f s, tree %.2f s, queries %.2f s (%.0f points/s)\n",
                  m.read_seconds, m.build_seconds, m.query_seconds,
                  m.query_seconds > 0.0 ? static_cast<double>(m.points) / m.query_seconds : 0.0);
    if (m.non_finite_points > 0)
      out += format("  %zu non-finite map points left out\n", m.non_finite_points);
  }
  if (!result.notes.empty()) {
    out += "\n";
    for (const std::string& note : result.notes) out += note + "\n";
  }
  return out;
}

}  // namespace storey::eval
