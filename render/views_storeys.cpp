// Top view of each storey: its points coloured by height above the floor,
// ceiling left out, the part of the trajectory walked on that storey.
#include <algorithm>
#include <cmath>

#include "render/palette.h"
#include "render/view_helpers.h"
#include "render/views.h"

namespace storey::render {
namespace {

NamedFigure storeyTop(const ViewContext& c, const StoreyEntry* storey) {
  const RunData& run = *c.run;
  const MapSample& m = run.map;
  double z_lo = -1e300, z_hi = 1e300;
  if (storey) storeyZRange(c, storey->index, z_lo, z_hi);
  std::vector<std::size_t> keep;
  double min_z = 1e300, max_z = -1e300;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (storey && m.storey[i] != storey->index) continue;
    const double z = m.positions[i].z();
    if (z >= z_hi) continue;
    keep.push_back(i);
    min_z = std::min(min_z, z);
    max_z = std::max(max_z, z);
  }
  const double base = storey ? storey->floor : (keep.empty() ? 0.0 : min_z);
  const double top = keep.empty() ? base + 1.0 : std::max(max_z, base + 0.5);
  Figure f;
  f.width = c.config.width;
  f.height = c.config.height;
  Panel panel;
  panel.view_direction = -Eigen::Vector3d::UnitZ();
  panel.view_up = c.axis_y;
  PointLayer points;
  points.size_px = static_cast<float>(c.config.point_size);
  points.positions.reserve(keep.size());
  points.colours.reserve(keep.size());
  for (std::size_t i : keep) {
    points.positions.push_back(m.positions[i]);
    points.colours.push_back(heightColour((m.positions[i].z() - base) / (top - base)));
  }
  panel.points.push_back(std::move(points));

  if (storey && storey->footprint.size() >= 3) {
    LineLayer footprint;
    footprint.colour = colours::kFootprint;
    footprint.width_px = 2.0f;
    footprint.dashed = true;
    std::vector<Eigen::Vector3d> loop;
    for (const auto& p : storey->footprint) loop.emplace_back(p.x(), p.y(), top + 0.1);
    loop.push_back(loop.front());
    footprint.polylines.push_back(std::move(loop));
    panel.lines.push_back(std::move(footprint));
  }
  LineLayer trajectory;
  trajectory.colour = colours::kTrajectory;
  trajectory.width_px = static_cast<float>(c.config.line_width);
  trajectory.polylines = trajectoryRuns(run.trajectory, [&](const Eigen::Vector3d& p) {
    return !storey || storeyOfElevation(run.storeys, p.z()) == storey->index;
  });
  const bool walked = !trajectory.polylines.empty();
  if (walked) {
    const Eigen::Vector3d start = trajectory.polylines.front().front();
    panel.labels.push_back({start, "  start", colours::kText, std::clamp(f.height / 55, 10, 22)});
  }
  panel.lines.push_back(std::move(trajectory));
  f.panels.push_back(std::move(panel));

  NamedFigure out;
  if (storey) {
    char name[32];
    std::snprintf(name, sizeof(name), "storey_%02d_top.png", storey->index);
    out.file = name;
    f.title = "Storey " + std::to_string(storey->index) + " from above, coloured by height";
    f.subtitle = c.run_name + " | orthographic top view, building x axis to the right | floor " +
                 fixed(storey->floor, 2) + " m" +
                 (z_hi < 1e299 ? ", points above " + fixed(z_hi, 2) + " m (ceiling) left out"
                               : std::string());
  } else {
    out.file = "map_top.png";
    f.title = "The map from above, coloured by height (no storey found)";
    f.subtitle = c.run_name + " | orthographic top view, building x axis to the right";
  }
  f.colour_bar =
      ColourBar{storey ? "height above the floor [m]" : "height above the lowest point [m]", 0.0,
                top - base, heightScale(64)};
  if (storey) {
    f.legend.push_back({LegendItem::Kind::kHeading, {}, "Storey " + std::to_string(storey->index)});
    f.legend.push_back(
        {LegendItem::Kind::kText,
         {},
         "floor " + fixed(storey->floor, 2) + " m" +
             (storey->ceiling ? ", ceiling " + fixed(*storey->ceiling, 2) + " m" : std::string())});
    f.legend.push_back(
        {LegendItem::Kind::kText, {}, "footprint area " + fixed(storey->area, 1) + " m\u00b2"});
    f.legend.push_back({LegendItem::Kind::kText,
                        {},
                        "points " + count(storey->points) + " (" + count(keep.size()) + " drawn)"});
  }
  f.legend.push_back({LegendItem::Kind::kHeading, {}, "Lines"});
  f.legend.push_back({LegendItem::Kind::kLine, colours::kTrajectory,
                      walked ? "trajectory on this storey" : "trajectory: not on this storey"});
  if (storey && storey->footprint.size() >= 3)
    f.legend.push_back({LegendItem::Kind::kLine, colours::kFootprint, "footprint (storeys.json)"});
  f.legend.push_back({LegendItem::Kind::kHeading, {}, "Run"});
  f.legend.push_back({LegendItem::Kind::kText, {}, mapLine(c, keep.size())});
  out.figure = std::move(f);
  return out;
}

}  // namespace

std::vector<NamedFigure> storeyTopFigures(const ViewContext& c) {
  std::vector<NamedFigure> out;
  if (c.run->storeys.empty()) {
    out.push_back(storeyTop(c, nullptr));
    return out;
  }
  for (const StoreyEntry& s : c.run->storeys) out.push_back(storeyTop(c, &s));
  return out;
}

}  // namespace storey::render
