#include "PlanePatch.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace storey::plugin {

namespace {

/// Unit vectors u, v with (u, v, n) right-handed; u horizontal when the plane is not.
void planeBasis(const Eigen::Vector3d& n, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  u = z.cross(n);
  if (u.norm() < 1e-6) u = Eigen::Vector3d::UnitX() - n * n.x();  // floor or ceiling
  u.normalize();
  v = n.cross(u);
}

}  // namespace

PlanePatch planePatch(const GlobalPlane& plane, const Trajectory& keyframes, double fallback_size) {
  PlanePatch patch;
  const Eigen::Vector3d n = plane.normal_world.normalized();
  patch.normal = n;
  planeBasis(n, patch.u, patch.v);
  const Eigen::Vector3d origin = n * plane.distance_world;  // closest point to the world origin

  double umin = std::numeric_limits<double>::infinity(), umax = -umin, vmin = umin, vmax = -umin;
  auto extend = [&](const Eigen::Vector3d& x_world) {
    const Eigen::Vector3d r = x_world - origin;
    const double a = r.dot(patch.u), b = r.dot(patch.v);
    umin = std::min(umin, a), umax = std::max(umax, a);
    vmin = std::min(vmin, b), vmax = std::max(vmax, b);
  };
  Eigen::Vector3d anchor_sum = Eigen::Vector3d::Zero();
  int anchors = 0;
  for (const PlaneObservation& o : plane.observations) {
    if (o.keyframe < 0 || o.keyframe >= static_cast<int>(keyframes.size())) continue;
    const Pose& T_world_lidar = keyframes[static_cast<std::size_t>(o.keyframe)].pose;
    for (const Eigen::Vector3d& h : o.hull_keyframe) extend(T_world_lidar * h);
    if (o.centroid_keyframe) {
      anchor_sum += T_world_lidar * *o.centroid_keyframe;
    } else {
      // The foot of the perpendicular from the sensor to the observed plane.
      const Eigen::Vector3d foot = o.normal_keyframe * o.distance_keyframe;
      anchor_sum += T_world_lidar * foot;
    }
    ++anchors;
  }
  if (std::isfinite(umin) && umax - umin > 1e-3 && vmax - vmin > 1e-3) {
    patch.from_hulls = true;
    patch.width = umax - umin;
    patch.height = vmax - vmin;
    patch.center = origin + patch.u * 0.5 * (umin + umax) + patch.v * 0.5 * (vmin + vmax);
    return patch;
  }
  const Eigen::Vector3d anchor = anchors > 0 ? Eigen::Vector3d(anchor_sum / anchors) : origin;
  patch.center = anchor - n * (n.dot(anchor) - plane.distance_world);
  patch.width = patch.height = fallback_size;
  return patch;
}

std::string planeKind(const GlobalPlane& plane, const Trajectory& keyframes) {
  const double cos20 = std::cos(20.0 * M_PI / 180.0);
  const Eigen::Vector3d n = plane.normal_world.normalized();
  const double nz = n.z();
  if (std::abs(nz) < std::sin(20.0 * M_PI / 180.0)) return "wall";
  if (std::abs(nz) < cos20) return "plane";
  double side = 0.0;  // > 0: seen from above
  if (plane.facing_world) {
    side = plane.facing_world->z();
  } else {
    for (const PlaneObservation& o : plane.observations) {
      if (o.keyframe < 0 || o.keyframe >= static_cast<int>(keyframes.size())) continue;
      const Eigen::Vector3d& x = keyframes[static_cast<std::size_t>(o.keyframe)].pose.translation();
      side += (n.dot(x) - plane.distance_world) * nz;
    }
  }
  return side >= 0.0 ? "floor" : "ceiling";
}

bool onPatch(const PlanePatch& patch, const Eigen::Vector3d& x, double tolerance, double margin) {
  const Eigen::Vector3d r = x - patch.center;
  if (std::abs(r.dot(patch.normal)) > tolerance) return false;
  return std::abs(r.dot(patch.u)) <= 0.5 * patch.width + margin &&
         std::abs(r.dot(patch.v)) <= 0.5 * patch.height + margin;
}

}  // namespace storey::plugin
