// SRP inspection: the global planes as coloured patches over the grey map,
// one panel per storey (the paper's Fig. 1), and one keyframe's SRPs.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "common/error.h"
#include "render/palette.h"
#include "render/view_helpers.h"
#include "render/views.h"

namespace storey::render {
namespace {

/// A patch is drawn filled when its seen side faces the viewer, otherwise as
/// an outline (so near walls and ceilings do not hide the storey).
PatchLayer::Patch drawnPatch(const WorldPatch& p, const Eigen::Vector3d& view_direction) {
  PatchLayer::Patch out;
  out.vertices = p.hull;
  out.colour = srpColour(p.plane_id);
  out.filled = p.facing.dot(view_direction) < 0.0;
  return out;
}

std::string storeyList(const std::set<int>& storeys) {
  std::string s;
  for (int i : storeys) s += (s.empty() ? "" : ",") + std::to_string(i);
  return s;
}

}  // namespace

Figure srpMapFigure(const ViewContext& c) {
  const RunData& run = *c.run;
  const MapSample& m = run.map;
  Figure f;
  f.width = c.config.width;
  f.height = c.config.height;
  f.title = "SRP inspection: global planes (SRPs) by storey";

  std::vector<int> storey_ids;
  for (const StoreyEntry& s : run.storeys) storey_ids.push_back(s.index);
  if (storey_ids.empty()) storey_ids.push_back(-1);  // one panel: the whole map
  const int n = static_cast<int>(storey_ids.size());
  const double scene_aspect = static_cast<double>(figureLayout(f.width, f.height).scene.width()) /
                              std::max(1, figureLayout(f.width, f.height).scene.height());
  int cols = 1;
  while (cols < n &&
         static_cast<double>(cols) / std::ceil(static_cast<double>(n) / cols) < scene_aspect * 0.9)
    ++cols;
  const int rows = (n + cols - 1) / cols;

  const Eigen::Vector3d view = oblique(horizontal(c, 35.0), 52.0);
  std::map<int, std::set<int>> storeys_of_plane;
  std::size_t drawn = 0;
  for (int k = 0; k < n; ++k) {
    const int storey = storey_ids[static_cast<std::size_t>(k)];
    Panel panel;
    panel.x0 = static_cast<double>(k % cols) / cols;
    panel.x1 = static_cast<double>(k % cols + 1) / cols;
    panel.y0 = static_cast<double>(k / cols) / rows;
    panel.y1 = static_cast<double>(k / cols + 1) / rows;
    panel.view_direction = view;
    panel.view_up = Eigen::Vector3d::UnitZ();
    double z_lo = -1e300, z_hi = 1e300;
    if (storey >= 0) storeyZRange(c, storey, z_lo, z_hi);
    double min_z = 1e300, max_z = -1e300;
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (storey >= 0 && m.storey[i] != storey) continue;
      if (m.positions[i].z() >= z_hi) continue;
      keep.push_back(i);
      min_z = std::min(min_z, static_cast<double>(m.positions[i].z()));
      max_z = std::max(max_z, static_cast<double>(m.positions[i].z()));
    }
    PointLayer points;
    points.size_px = static_cast<float>(c.config.point_size);
    for (std::size_t i : keep) {
      points.positions.push_back(m.positions[i]);
      const int srp = c.srp_of_point[i];
      points.colours.push_back(
          srp >= 0 ? srpColour(srp)
                   : mapGrey((m.positions[i].z() - min_z) / std::max(max_z - min_z, 0.1)));
    }
    drawn += keep.size();
    panel.points.push_back(std::move(points));
    PatchLayer patches;
    patches.outline_px = 2.0f;
    // Patches above the storey's ceiling (e.g. a storey the segmentation missed)
    // would hide it: left out, like the points.
    const double patch_top = z_hi + c.config.ceiling_cut + 0.1;
    for (const WorldPatch& p : c.patches.patches) {
      const int s = storeyOfElevation(run.storeys, p.centroid.z());
      if (storey >= 0 && s != storey) continue;
      if (p.centroid.z() > patch_top) continue;
      patches.patches.push_back(drawnPatch(p, view));
      storeys_of_plane[p.plane_id].insert(s);
    }
    panel.patches.push_back(std::move(patches));
    if (storey >= 0) {
      const StoreyEntry& e = *std::find_if(run.storeys.begin(), run.storeys.end(),
                                           [&](const StoreyEntry& s) { return s.index == storey; });
      panel.caption = "storey " + std::to_string(storey) + " (floor " + fixed(e.floor, 2) + " m)";
    } else {
      panel.caption = run.storeys.empty() ? "whole map (no storey found)" : "whole map";
    }
    f.panels.push_back(std::move(panel));
  }
  f.subtitle = c.run_name + " | " + std::to_string(run.planes.size()) + " SRPs, " +
               count(c.patches.patches.size()) +
               " observations as patches | oblique view from above, orthographic";
  if (c.patches.estimated > 0)
    f.subtitle += " | patches estimated from the map (planes.json has no hulls)";

  f.legend.push_back({LegendItem::Kind::kHeading, {}, "SRP id: kind, observations, storeys"});
  for (const GlobalPlane& p : run.planes) {
    const auto it = storeys_of_plane.find(p.id);
    std::string text = "#" + std::to_string(p.id) + " " + planeKind(p.normal_world, facingOf(p)) +
                       ", " + std::to_string(p.observations.size()) + " obs.";
    if (it == storeys_of_plane.end())
      text += ", not shown (above the ceilings)";
    else if (!(it->second.size() == 1 && *it->second.begin() < 0))
      text += ", st. " + storeyList(it->second);
    f.legend.push_back({LegendItem::Kind::kSwatch, srpColour(p.id), text});
  }
  if (run.planes.empty())
    f.legend.push_back({LegendItem::Kind::kText, {}, "no SRP in planes.json"});
  f.legend.push_back({LegendItem::Kind::kHeading, {}, "How to read"});
  f.legend.push_back({LegendItem::Kind::kText, {}, "filled: seen side towards you"});
  f.legend.push_back({LegendItem::Kind::kText, {}, "outline: seen from behind"});
  f.legend.push_back({LegendItem::Kind::kSwatch, mapGrey(0.5), "map, lighter = higher"});
  f.legend.push_back({LegendItem::Kind::kText, {}, mapLine(c, drawn)});
  return f;
}

int keyframeWithMostSrps(const ViewContext& c) {
  std::map<int, int> counts;
  for (const WorldPatch& p : c.patches.patches) ++counts[p.keyframe];
  int best = -1, best_count = 0;
  for (const auto& [k, n] : counts)
    if (n > best_count) best = k, best_count = n;
  return best;
}

Figure srpKeyframeFigure(const ViewContext& c, int keyframe) {
  const RunData& run = *c.run;
  if (keyframe < 0 || keyframe >= static_cast<int>(run.keyframes.size())) {
    throw Error("keyframe " + std::to_string(keyframe) + " does not exist: keyframes.tum of " +
                run.dir + " has " + std::to_string(run.keyframes.size()) + " keyframes (0 to " +
                std::to_string(static_cast<int>(run.keyframes.size()) - 1) + ")");
  }
  const StampedPose& kf = run.keyframes[static_cast<std::size_t>(keyframe)];
  const Pose& T_world_lidar = kf.pose;
  const Eigen::Vector3d at = T_world_lidar.translation();
  std::vector<int> mine;
  for (std::size_t i = 0; i < c.patches.patches.size(); ++i)
    if (c.patches.patches[i].keyframe == keyframe) mine.push_back(static_cast<int>(i));
  const MapSample& m = run.map;
  const std::vector<int> on_mine =
      srpOfPoints(m, c.patches.patches, c.config.srp_point_distance, mine);

  // The storey the keyframe is on, ceiling cut; or +-2.5 m around it.
  double z_lo = at.z() - 2.5, z_hi = at.z() + 2.5;
  const int storey = storeyOfElevation(run.storeys, at.z());
  if (storey >= 0) {
    storeyZRange(c, storey, z_lo, z_hi);
    z_lo = std::max(z_lo, at.z() - 4.0);
  }
  const double r2 = c.config.keyframe_radius * c.config.keyframe_radius;
  Figure f;
  f.width = c.config.width;
  f.height = c.config.height;
  Eigen::Vector3d heading = T_world_lidar.rotationMatrix().col(0);
  heading.z() = 0.0;
  if (heading.norm() < 1e-6) heading = c.axis_x;
  // From behind the sensor, turned 30 degrees so walls along the heading are not seen edge-on.
  const Eigen::Vector3d view = oblique(
      Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()) * heading.normalized(),
      55.0);
  Panel panel;
  panel.view_direction = view;
  panel.view_up = Eigen::Vector3d::UnitZ();
  PointLayer points;
  points.size_px = static_cast<float>(c.config.point_size);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const Eigen::Vector3d p = m.positions[i].cast<double>();
    if ((p - at).head<2>().squaredNorm() > r2 || p.z() < z_lo || p.z() >= z_hi) continue;
    points.positions.push_back(m.positions[i]);
    points.colours.push_back(on_mine[i] >= 0
                                 ? srpColour(on_mine[i])
                                 : mapGrey((p.z() - z_lo) / std::max(z_hi - z_lo, 0.1)));
  }
  const std::size_t drawn = points.positions.size();
  panel.points.push_back(std::move(points));
  PatchLayer patches;
  for (int i : mine)
    patches.patches.push_back(drawnPatch(c.patches.patches[static_cast<std::size_t>(i)], view));
  panel.patches.push_back(std::move(patches));

  LineLayer trajectory;
  trajectory.colour = colours::kTrajectory;
  trajectory.width_px = static_cast<float>(c.config.line_width) * 0.7f;
  trajectory.polylines = trajectoryRuns(run.trajectory, [&](const Eigen::Vector3d& p) {
    return (p - at).head<2>().squaredNorm() <= r2 && p.z() >= z_lo && p.z() < z_hi + 1.0;
  });
  panel.lines.push_back(std::move(trajectory));
  const Rgb axis_colours[3] = {{200, 0, 0}, {0, 150, 0}, {0, 0, 220}};
  for (int k = 0; k < 3; ++k) {
    LineLayer axis;
    axis.colour = axis_colours[k];
    axis.width_px = static_cast<float>(c.config.line_width) + 1.0f;
    axis.polylines.push_back({at, at + T_world_lidar.rotationMatrix().col(k)});
    panel.lines.push_back(std::move(axis));
  }
  panel.labels.push_back({at + 0.3 * Eigen::Vector3d::UnitZ(),
                          "  keyframe " + std::to_string(keyframe), colours::kText,
                          std::clamp(f.height / 55, 10, 22)});
  f.panels.push_back(std::move(panel));

  f.title = "SRP inspection: keyframe " + std::to_string(keyframe) + " and its " +
            std::to_string(mine.size()) + " SRPs";
  f.subtitle = c.run_name + " | t = " + fixed(kf.time, 3) + " s | map within " +
               fixed(c.config.keyframe_radius, 0) + " m, " +
               (storey >= 0 ? "storey " + std::to_string(storey) + ", ceiling left out"
                            : std::string("+-2.5 m in z")) +
               " | oblique view from behind the sensor";
  f.legend.push_back({LegendItem::Kind::kHeading, {}, "SRPs of this keyframe"});
  f.legend.push_back({LegendItem::Kind::kText, {}, "id: kind, n, d in the LiDAR frame"});
  for (int i : mine) {
    const WorldPatch& p = c.patches.patches[static_cast<std::size_t>(i)];
    const GlobalPlane& plane = run.planes[static_cast<std::size_t>(p.plane_index)];
    const PlaneObservation& o = plane.observations[static_cast<std::size_t>(p.observation)];
    std::string text = "#" + std::to_string(p.plane_id) + " " + planeKind(p.normal, p.facing) +
                       ": n (" + fixed(o.normal_keyframe.x(), 2) + " " +
                       fixed(o.normal_keyframe.y(), 2) + " " + fixed(o.normal_keyframe.z(), 2) +
                       "), d " + fixed(o.distance_keyframe, 2) + " m";
    f.legend.push_back({LegendItem::Kind::kSwatch, srpColour(p.plane_id), text});
    f.legend.push_back({LegendItem::Kind::kText,
                        {},
                        "    " + count(static_cast<std::size_t>(o.points)) + " pts, rms " +
                            fixed(o.fit_rms * 100.0, 1) + " cm" + (o.outlier ? ", OUTLIER" : "")});
  }
  if (mine.empty())
    f.legend.push_back({LegendItem::Kind::kText, {}, "none (no SRP extracted here)"});
  f.legend.push_back({LegendItem::Kind::kHeading, {}, "Other"});
  f.legend.push_back({LegendItem::Kind::kSwatch, mapGrey(0.5), "map, lighter = higher"});
  f.legend.push_back({LegendItem::Kind::kLine, colours::kTrajectory, "trajectory"});
  f.legend.push_back({LegendItem::Kind::kLine, axis_colours[0], "LiDAR x (1 m)"});
  f.legend.push_back({LegendItem::Kind::kLine, axis_colours[1], "LiDAR y"});
  f.legend.push_back({LegendItem::Kind::kLine, axis_colours[2], "LiDAR z"});
  f.legend.push_back({LegendItem::Kind::kText, {}, count(drawn) + " map points drawn"});
  return f;
}

}  // namespace storey::render
