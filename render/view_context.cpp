// The shared state of the views, and the helpers of view_helpers.h.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "render/view_helpers.h"
#include "render/views.h"

namespace storey::render {

double buildingYaw(const std::vector<GlobalPlane>& planes) {
  double c = 0.0, s = 0.0;
  for (const GlobalPlane& p : planes) {
    if (std::abs(p.normal_world.z()) > 0.3) continue;  // not a wall
    const double angle = std::atan2(p.normal_world.y(), p.normal_world.x());
    const double w = static_cast<double>(std::max<std::size_t>(1, p.observations.size()));
    c += w * std::cos(4.0 * angle);
    s += w * std::sin(4.0 * angle);
  }
  if (c * c + s * s < 1e-12) return 0.0;
  return std::atan2(s, c) / 4.0;
}

std::string planeKind(const Eigen::Vector3d& normal, const Eigen::Vector3d& facing) {
  const double vertical = std::abs(normal.normalized().z());
  if (vertical > std::cos(20.0 * M_PI / 180.0)) return facing.z() > 0.0 ? "floor" : "ceiling";
  if (vertical < std::sin(20.0 * M_PI / 180.0)) return "wall";
  return "slanted";
}

ViewContext makeViewContext(const RunData& run, const RenderConfig& config) {
  ViewContext c;
  c.run = &run;
  c.config = config;
  std::filesystem::path dir(run.dir);
  c.run_name = (dir.has_filename() ? dir.filename() : dir.parent_path().filename()).string();
  if (c.run_name.empty()) c.run_name = run.dir;
  c.building_yaw = buildingYaw(run.planes);
  c.axis_x = {std::cos(c.building_yaw), std::sin(c.building_yaw), 0.0};
  c.axis_y = {-std::sin(c.building_yaw), std::cos(c.building_yaw), 0.0};
  c.patches = worldPatches(run, config.srp_point_distance, std::min(config.keyframe_radius, 8.0));
  c.srp_of_point = srpOfPoints(run.map, c.patches.patches, config.srp_point_distance);
  return c;
}

std::vector<Eigen::Vector3d> polyline(const Trajectory& trajectory) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) out.push_back(p.pose.translation());
  return out;
}

std::string fixed(double value, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, value);
  std::string s = buf;
  if (s == "-0" || s.rfind("-0.", 0) == 0) {
    bool zero = true;
    for (char ch : s)
      if (ch >= '1' && ch <= '9') zero = false;
    if (zero) s = s.substr(1);
  }
  return s;
}

std::string count(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ' ';
    out += digits[i];
  }
  return out;
}

void storeyZRange(const ViewContext& context, int storey_index, double& lo, double& hi) {
  lo = -1e300;
  hi = 1e300;
  const auto& storeys = context.run->storeys;
  for (std::size_t i = 0; i < storeys.size(); ++i) {
    const StoreyEntry& s = storeys[i];
    if (s.index != storey_index) continue;
    lo = i == 0 ? -1e300 : s.floor - 0.15;
    if (s.ceiling)
      hi = *s.ceiling - context.config.ceiling_cut;
    else if (i + 1 < storeys.size())
      hi = storeys[i + 1].floor - 0.15 - context.config.ceiling_cut;
  }
}

std::string mapLine(const ViewContext& context, std::size_t drawn) {
  const MapSample& m = context.run->map;
  if (m.file_points == 0) return "no map.ply";
  return count(drawn) + " of " + count(m.file_points) + " map points drawn";
}

Eigen::Vector3d horizontal(const ViewContext& context, double degrees) {
  const double a = degrees * M_PI / 180.0;
  return (std::cos(a) * context.axis_x + std::sin(a) * context.axis_y).normalized();
}

Eigen::Vector3d oblique(const Eigen::Vector3d& h, double elevation_deg) {
  const double e = elevation_deg * M_PI / 180.0;
  return (std::cos(e) * h.normalized() - std::sin(e) * Eigen::Vector3d::UnitZ()).normalized();
}

}  // namespace storey::render
