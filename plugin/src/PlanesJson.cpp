#include "PlanesJson.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace storey::plugin {

namespace {

Eigen::Vector3d vec3(const nlohmann::json& j, const char* what) {
  if (!j.is_array() || j.size() != 3) throw Error(std::string("planes.json: ") + what + " is not [x, y, z]");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

/// Unit vectors u, v with (u, v, n) right-handed; u horizontal when the plane is not.
void planeBasis(const Eigen::Vector3d& n, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  u = z.cross(n);
  if (u.norm() < 1e-6) u = Eigen::Vector3d::UnitX() - n * n.x();  // floor or ceiling
  u.normalize();
  v = n.cross(u);
}

}  // namespace

std::vector<GlobalPlane> parsePlanesJson(const std::string& json_text) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("planes.json: not JSON: ") + e.what());
  }
  if (!doc.is_object() || !doc.contains("planes") || !doc["planes"].is_array())
    throw Error("planes.json: no \"planes\" array");
  std::vector<GlobalPlane> planes;
  try {
    for (const auto& p : doc["planes"]) {
      GlobalPlane plane;
      plane.id = p.at("id").get<int>();
      plane.normal = vec3(p.at("normal"), "normal").normalized();
      plane.distance = p.at("distance").get<double>();
      if (p.contains("facing")) plane.facing = vec3(p["facing"], "facing");
      if (p.contains("observations")) {
        for (const auto& o : p["observations"]) {
          PlaneObservation obs;
          obs.keyframe = o.at("keyframe").get<int>();
          obs.normal = vec3(o.at("normal"), "observation normal");
          obs.distance = o.at("distance").get<double>();
          obs.points = o.value("points", 0L);
          obs.fit_rms = o.value("fit_rms_m", 0.0);
          obs.residual_chi2 = o.value("residual_chi2", 0.0);
          obs.outlier = o.value("outlier", false);
          if (o.contains("centroid")) obs.centroid = vec3(o["centroid"], "centroid");
          if (o.contains("hull") && o["hull"].is_array())
            for (const auto& h : o["hull"])
              if (h.is_array() && h.size() == 3) obs.hull.push_back(vec3(h, "hull point"));
          plane.observations.push_back(std::move(obs));
        }
      }
      planes.push_back(std::move(plane));
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("planes.json: ") + e.what());
  }
  return planes;
}

PlanePatch planePatch(const GlobalPlane& plane, const Trajectory& keyframes, double fallback_size) {
  PlanePatch patch;
  patch.normal = plane.normal;
  planeBasis(plane.normal, patch.u, patch.v);
  const Eigen::Vector3d origin = plane.normal * plane.distance;  // closest point to the world origin

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
    for (const Eigen::Vector3d& h : o.hull) extend(T_world_lidar * h);
    if (o.centroid) {
      anchor_sum += T_world_lidar * *o.centroid;
    } else {
      // The foot of the perpendicular from the sensor to the observed plane.
      const Eigen::Vector3d foot = o.normal * o.distance;
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
  patch.center = anchor - plane.normal * (plane.normal.dot(anchor) - plane.distance);
  patch.width = patch.height = fallback_size;
  return patch;
}

std::string planeKind(const GlobalPlane& plane, const Trajectory& keyframes) {
  const double cos20 = std::cos(20.0 * M_PI / 180.0);
  const double nz = plane.normal.z();
  if (std::abs(nz) < std::sin(20.0 * M_PI / 180.0)) return "wall";
  if (std::abs(nz) < cos20) return "plane";
  double side = 0.0;  // > 0: seen from above
  if (plane.facing) {
    side = plane.facing->z();
  } else {
    for (const PlaneObservation& o : plane.observations) {
      if (o.keyframe < 0 || o.keyframe >= static_cast<int>(keyframes.size())) continue;
      const Eigen::Vector3d& x = keyframes[static_cast<std::size_t>(o.keyframe)].pose.translation();
      side += (plane.normal.dot(x) - plane.distance) * nz;
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
