#include "odometry/scan_matcher.h"

#include <cmath>

namespace storey {

const char* toString(MatchReject reason) {
  switch (reason) {
    case MatchReject::kTooFewNeighbours: return "too few map neighbours";
    case MatchReject::kNotPlanar: return "neighbours not planar";
    case MatchReject::kNotALine: return "neighbours not a line";
    case MatchReject::kTooFar: return "too far from plane or line";
    case MatchReject::kOtherSide: return "seen from the other side of the plane";
    case MatchReject::kCount: break;
  }
  return "unknown";
}

MatchResult matchFeatures(const std::vector<Eigen::Vector3d>& planes_imu,
                          const std::vector<Eigen::Vector3d>& edges_imu, const Pose& T_world_imu,
                          const VoxelMap& plane_map, const VoxelMap& edge_map,
                          const OdometryConfig& config, const Eigen::Vector3d& sensor_imu) {
  MatchResult result;
  const auto reject = [&](MatchReject reason) { ++result.rejected[static_cast<std::size_t>(reason)]; };
  const float max_neighbour = static_cast<float>(config.max_neighbour_distance);
  Eigen::Vector3f neighbours[VoxelMap::kMaxNeighbours];
  Eigen::Vector3f views[VoxelMap::kMaxNeighbours];
  const Eigen::Vector3d sensor_world = T_world_imu * sensor_imu;
  result.planes.reserve(planes_imu.size());
  for (const Eigen::Vector3d& y : planes_imu) {
    const Eigen::Vector3d x = T_world_imu * y;
    const int found =
        plane_map.nearest(x.cast<float>(), config.neighbours, max_neighbour, neighbours, views);
    if (found < config.neighbours) {
      reject(MatchReject::kTooFewNeighbours);
      continue;
    }
    const PlaneFit fit = fitPlane(neighbours, found, config.plane_fit_tolerance);
    if (!fit.valid) {
      reject(MatchReject::kNotPlanar);
      continue;
    }
    if (std::abs(fit.normal.dot(x) - fit.d) > config.max_point_distance) {
      reject(MatchReject::kTooFar);
      continue;
    }
    // Side: the summed view directions of the neighbours tell which side of
    // the plane they were seen from (zero when the map keeps no views).
    Eigen::Vector3f view_sum = Eigen::Vector3f::Zero();
    for (int i = 0; i < found; ++i) view_sum += views[i];
    const double map_side = fit.normal.dot(view_sum.cast<double>());
    if (map_side != 0.0 && map_side * fit.normal.dot(sensor_world - x) < 0.0) {
      reject(MatchReject::kOtherSide);
      continue;
    }
    result.planes.push_back({y, fit.normal, fit.d, std::hypot(config.point_sigma, fit.thickness)});
  }
  result.lines.reserve(edges_imu.size());
  for (const Eigen::Vector3d& y : edges_imu) {
    const Eigen::Vector3d x = T_world_imu * y;
    const int found = edge_map.nearest(x.cast<float>(), config.neighbours, max_neighbour, neighbours);
    if (found < config.neighbours) {
      reject(MatchReject::kTooFewNeighbours);
      continue;
    }
    const LineFit fit = fitLine(neighbours, found, config.line_eigen_ratio);
    if (!fit.valid) {
      reject(MatchReject::kNotALine);
      continue;
    }
    if ((x - fit.point).cross(fit.direction).norm() > config.max_point_distance) {
      reject(MatchReject::kTooFar);
      continue;
    }
    result.lines.push_back({y, fit.point, fit.direction, std::hypot(config.point_sigma, fit.thickness)});
  }
  return result;
}

}  // namespace storey
