// Elevation of the whole building (front and side): the paper's Fig. 6 view.
#include <cmath>

#include "render/palette.h"
#include "render/view_helpers.h"
#include "render/views.h"

namespace storey::render {

Figure elevationFigure(const ViewContext& c, bool side) {
  const RunData& run = *c.run;
  Figure f;
  f.width = c.config.width;
  f.height = c.config.height;
  f.title = side ? "Elevation, side view: the building by storey"
                 : "Elevation, front view: the building by storey";
  Panel panel;
  // Front: looking along the building's y axis (x to the right); side: along -x (y to the right).
  panel.view_direction = side ? Eigen::Vector3d(-c.axis_x) : c.axis_y;
  panel.view_up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d across = side ? c.axis_y : c.axis_x;
  f.subtitle = c.run_name + " | orthographic, looking along the building's " +
               (side ? std::string("-x") : std::string("+y")) + " axis (walls at " +
               fixed(c.building_yaw * 180.0 / M_PI, 1) + " deg in the world frame) | z up";

  PointLayer points;
  points.size_px = static_cast<float>(c.config.point_size);
  bool any_stairs = false, any_none = false;
  double lo = 1e300, hi = -1e300;
  const MapSample& m = run.map;
  points.positions = m.positions;
  points.colours.resize(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (m.stairs[i]) {
      points.colours[i] = colours::kStairs;
      any_stairs = true;
    } else {
      points.colours[i] = storeyColour(m.storey[i]);
      any_none |= m.storey[i] < 0;
    }
    const double a = m.positions[i].cast<double>().dot(across);
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  panel.points.push_back(std::move(points));
  for (const StampedPose& p : run.trajectory) {
    const double a = p.pose.translation().dot(across);
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }

  // Floor elevations as dashed lines across the building, labelled at the left.
  LineLayer floors;
  floors.colour = colours::kFloorLine;
  floors.width_px = 1.5f;
  floors.dashed = true;
  floors.on_top = true;
  const double margin = 0.04 * (hi - lo) + 0.5;
  const Eigen::Vector3d depth = panel.view_direction.normalized();
  for (const StoreyEntry& s : run.storeys) {
    const Eigen::Vector3d a =
        (lo - margin) * across + s.floor * Eigen::Vector3d::UnitZ() - 50.0 * depth;
    const Eigen::Vector3d b =
        (hi + margin) * across + s.floor * Eigen::Vector3d::UnitZ() - 50.0 * depth;
    floors.polylines.push_back({a, b});
    panel.labels.push_back(
        {a + Eigen::Vector3d(0, 0, 0.15),
         "storey " + std::to_string(s.index) + ": floor " + fixed(s.floor, 2) + " m",
         colours::kText, std::clamp(f.height / 60, 10, 22)});
  }
  if (!floors.polylines.empty()) panel.lines.push_back(floors);

  LineLayer trajectory;
  trajectory.colour = colours::kTrajectory;
  trajectory.width_px = static_cast<float>(c.config.line_width);
  trajectory.polylines.push_back(polyline(run.trajectory));
  panel.lines.push_back(std::move(trajectory));
  f.panels.push_back(std::move(panel));

  f.legend.push_back({LegendItem::Kind::kHeading, {}, "Storeys (map points)"});
  if (run.storeys.empty()) f.legend.push_back({LegendItem::Kind::kText, {}, "no storey found"});
  for (const StoreyEntry& s : run.storeys) {
    std::string text = "storey " + std::to_string(s.index) + ": floor " + fixed(s.floor, 2) + " m";
    if (s.ceiling) text += ", ceiling " + fixed(*s.ceiling, 2) + " m";
    f.legend.push_back({LegendItem::Kind::kSwatch, storeyColour(s.index), text});
  }
  if (any_stairs) f.legend.push_back({LegendItem::Kind::kSwatch, colours::kStairs, "stairs"});
  if (any_none) f.legend.push_back({LegendItem::Kind::kSwatch, storeyColour(-1), "no storey"});
  f.legend.push_back({LegendItem::Kind::kHeading, {}, "Lines"});
  f.legend.push_back(
      {LegendItem::Kind::kLine, colours::kTrajectory, "trajectory (trajectory.tum)"});
  if (!run.storeys.empty())
    f.legend.push_back(
        {LegendItem::Kind::kLine, colours::kFloorLine, "floor elevation (storeys.json)"});
  f.legend.push_back({LegendItem::Kind::kHeading, {}, "Run"});
  f.legend.push_back({LegendItem::Kind::kText, {}, mapLine(c, m.size())});
  f.legend.push_back(
      {LegendItem::Kind::kText, {}, "trajectory: " + count(run.trajectory.size()) + " poses"});
  return f;
}

}  // namespace storey::render
