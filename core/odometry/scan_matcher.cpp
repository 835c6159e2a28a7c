#include "odometry/scan_matcher.h"

#include "common/parallel_chunks.h"

#include <algorithm>
#include <cmath>

namespace storey {

const char* toString(MatchReject reason) {
  switch (reason) {
    case MatchReject::kTooFewNeighbours:
      return "too few map neighbours";
    case MatchReject::kNotPlanar:
      return "neighbours not planar";
    case MatchReject::kNotALine:
      return "neighbours not a line";
    case MatchReject::kTooFar:
      return "too far from plane or line";
    case MatchReject::kOtherSide:
      return "seen from the other side of the plane";
    case MatchReject::kCount:
      break;
  }
  return "unknown";
}

namespace {

/// Matches planar features [begin, end) into `result` (planes and rejects).
void matchPlanes(const std::vector<Eigen::Vector3d>& planes_imu, std::size_t begin, std::size_t end,
                 const Pose& T_world_imu, const VoxelMap& plane_map, const OdometryConfig& config,
                 const Eigen::Vector3d& sensor_world, MatchResult& result) {
  const auto reject = [&](MatchReject reason) {
    ++result.rejected[static_cast<std::size_t>(reason)];
  };
  const float max_neighbour = static_cast<float>(config.max_neighbour_distance);
  Eigen::Vector3f neighbours[VoxelMap::kMaxNeighbours];
  Eigen::Vector3f views[VoxelMap::kMaxNeighbours];
  result.planes.reserve(result.planes.size() + (end - begin));
  for (std::size_t f = begin; f < end; ++f) {
    const Eigen::Vector3d& y = planes_imu[f];
    const Eigen::Vector3d x = T_world_imu * y;
    const Eigen::Vector3f x_f = x.cast<float>();
    const int found = plane_map.nearest(x_f, config.neighbours, max_neighbour, neighbours, views);
    if (found < config.neighbours) {
      reject(MatchReject::kTooFewNeighbours);
      continue;
    }
    // With plane_fit_min_inliers, the query's own face when the neighbours
    // span two surfaces (a tread, not tread and riser together).
    std::uint32_t face = ~0u;
    const PlaneFit fit = config.plane_fit_min_inliers > 0
                             ? fitPlaneLargestFace(neighbours, found, config.plane_fit_tolerance,
                                                   config.plane_fit_min_inliers, &face, &x_f)
                             : fitPlane(neighbours, found, config.plane_fit_tolerance);
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
    for (int i = 0; i < found; ++i)
      if (face & (1u << i)) view_sum += views[i];
    const double map_side = fit.normal.dot(view_sum.cast<double>());
    if (map_side != 0.0 && map_side * fit.normal.dot(sensor_world - x) < 0.0) {
      reject(MatchReject::kOtherSide);
      continue;
    }
    result.planes.push_back({y, fit.normal, fit.d, std::hypot(config.point_sigma, fit.thickness)});
  }
}

}  // namespace

MatchResult matchFeatures(const std::vector<Eigen::Vector3d>& planes_imu,
                          const std::vector<Eigen::Vector3d>& edges_imu, const Pose& T_world_imu,
                          const VoxelMap& plane_map, const VoxelMap& edge_map,
                          const OdometryConfig& config, const Eigen::Vector3d& sensor_imu,
                          const ParallelChunks* parallel) {
  MatchResult result;
  const auto reject = [&](MatchReject reason) {
    ++result.rejected[static_cast<std::size_t>(reason)];
  };
  const float max_neighbour = static_cast<float>(config.max_neighbour_distance);
  Eigen::Vector3f neighbours[VoxelMap::kMaxNeighbours];
  const Eigen::Vector3d sensor_world = T_world_imu * sensor_imu;
  // Planar features in chunks of a fixed size, joined in order: the same
  // matches whatever the number of threads.
  constexpr std::size_t kChunk = 256;
  const std::size_t chunks = (planes_imu.size() + kChunk - 1) / kChunk;
  if (parallel != nullptr && parallel->threads() > 1 && chunks > 1) {
    std::vector<MatchResult> parts(chunks);
    parallel->run(chunks, [&](std::size_t c) {
      matchPlanes(planes_imu, c * kChunk, std::min(planes_imu.size(), (c + 1) * kChunk),
                  T_world_imu, plane_map, config, sensor_world, parts[c]);
    });
    result.planes.reserve(planes_imu.size());
    for (const MatchResult& part : parts) {
      result.planes.insert(result.planes.end(), part.planes.begin(), part.planes.end());
      for (std::size_t r = 0; r < result.rejected.size(); ++r)
        result.rejected[r] += part.rejected[r];
    }
  } else {
    matchPlanes(planes_imu, 0, planes_imu.size(), T_world_imu, plane_map, config, sensor_world,
                result);
  }
  result.lines.reserve(edges_imu.size());
  for (const Eigen::Vector3d& y : edges_imu) {
    const Eigen::Vector3d x = T_world_imu * y;
    const int found =
        edge_map.nearest(x.cast<float>(), config.neighbours, max_neighbour, neighbours);
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
    result.lines.push_back(
        {y, fit.point, fit.direction, std::hypot(config.point_sigma, fit.thickness)});
  }
  return result;
}

}  // namespace storey
