// Estimated vs true trajectory (and other runs, e.g. --no-srp), top and front.
#include <cmath>

#include "common/error.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/evaluation.h"
#include "render/palette.h"
#include "render/view_helpers.h"
#include "render/views.h"

namespace storey::render {
namespace {

Trajectory transformed(const Trajectory& t, const Pose& T_to_from) {
  Trajectory out = t;
  for (StampedPose& p : out) p.pose = T_to_from * p.pose;
  return out;
}

Rgb estimateColour(std::size_t i) {
  if (i == 0) return colours::kEstimate;
  if (i == 1) return colours::kComparison;
  return srpColour(static_cast<int>(i) + 2);
}

}  // namespace

TrajectoryComparison compareTrajectories(const Trajectory& truth, const std::string& truth_name,
                                         const std::vector<NamedTrajectory>& estimates) {
  if (estimates.empty() || estimates.front().trajectory.size() < 2)
    throw Error("trajectory comparison: the run's trajectory has fewer than 2 poses");
  TrajectoryComparison out;
  out.estimates = estimates;
  const Trajectory& run = estimates.front().trajectory;
  const eval::AssociatedPoses pairs = eval::associate(truth, run);
  if (pairs.matched() < 2) {
    throw Error(truth_name + ": fewer than 2 of its poses overlap the run's trajectory in time (" +
                std::to_string(pairs.matched()) + " matched): is it the ground truth of this log?");
  }
  const Pose first = pairs.T_world_gt.front().inverse() * pairs.T_world_est.front();
  eval::Alignment alignment = eval::Alignment::kNone;
  Pose T_run_truth;
  if (first.translation().norm() > 0.05 || first.angle() > 1.0 * M_PI / 180.0) {
    alignment = eval::Alignment::kYawTranslation;
    eval::Positions p_est, p_gt;
    for (std::size_t i = 0; i < pairs.matched(); ++i) {
      p_est.push_back(pairs.T_world_est[i].translation());
      p_gt.push_back(pairs.T_world_gt[i].translation());
    }
    T_run_truth = eval::align(alignment, p_est, p_gt).inverse();
    out.alignment = "truth aligned to the run (yaw + translation, least squares)";
  } else {
    out.alignment = "truth and run in the same world frame (no alignment)";
  }
  out.truth = {truth_name, transformed(truth, T_run_truth)};
  for (const NamedTrajectory& e : estimates) {
    std::string note = e.name;
    try {
      const eval::TrajectoryEvaluation ev = eval::evaluateTrajectory(truth, e.trajectory);
      note += ": ATE " + fixed(ev.ateWith(alignment).translation.rmse, 3) + " m, end drift " +
              fixed(ev.est_drift.dxyz, 3) + " m";
    } catch (const Error& error) {
      note += ": no ATE (" + std::string(error.what()) + ")";
    }
    out.legend_notes.push_back(note);
  }
  return out;
}

Figure trajectoryFigure(const ViewContext& c, const TrajectoryComparison& comparison, bool top) {
  const RunData& run = *c.run;
  Figure f;
  f.width = c.config.width;
  f.height = c.config.height;
  f.title = std::string("Trajectories against ground truth, ") + (top ? "top view" : "front view");
  f.subtitle =
      c.run_name + " | " + comparison.alignment + " | orthographic, " +
      (top ? "building x axis to the right" : "looking along the building's +y axis, z up");
  Panel panel;
  panel.view_direction = top ? Eigen::Vector3d(-Eigen::Vector3d::UnitZ()) : c.axis_y;
  panel.view_up = top ? c.axis_y : Eigen::Vector3d::UnitZ();
  PointLayer context;
  context.size_px = 1.0f;
  const std::size_t step = std::max<std::size_t>(1, run.map.size() / 400000);
  for (std::size_t i = 0; i < run.map.size(); i += step) {
    context.positions.push_back(run.map.positions[i]);
    context.colours.push_back(colours::kContext);
  }
  panel.points.push_back(std::move(context));
  const float width = static_cast<float>(c.config.line_width);
  LineLayer truth;
  truth.colour = colours::kTruth;
  truth.width_px = width + 1.0f;
  truth.polylines.push_back(polyline(comparison.truth.trajectory));
  panel.lines.push_back(std::move(truth));
  for (std::size_t i = 0; i < comparison.estimates.size(); ++i) {
    LineLayer line;
    line.colour = estimateColour(i);
    line.width_px = std::max(1.0f, width - 1.0f);
    line.polylines.push_back(polyline(comparison.estimates[i].trajectory));
    panel.lines.push_back(std::move(line));
  }
  const Eigen::Vector3d start = comparison.truth.trajectory.front().pose.translation();
  panel.labels.push_back({start, "  start", colours::kText, std::clamp(f.height / 55, 10, 22)});
  f.panels.push_back(std::move(panel));

  f.legend.push_back({LegendItem::Kind::kHeading, {}, "Trajectories"});
  f.legend.push_back(
      {LegendItem::Kind::kLine, colours::kTruth, "ground truth: " + comparison.truth.name});
  for (std::size_t i = 0; i < comparison.estimates.size(); ++i)
    f.legend.push_back({LegendItem::Kind::kLine, estimateColour(i), comparison.legend_notes[i]});
  f.legend.push_back({LegendItem::Kind::kHeading, {}, "Context"});
  f.legend.push_back({LegendItem::Kind::kSwatch, colours::kContext, "map (light grey)"});
  return f;
}

}  // namespace storey::render
