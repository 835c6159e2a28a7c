#pragma once
/// Data association of the odometry: each feature point (IMU frame) is placed
/// in the world with the current pose estimate, its nearest map points are
/// found, and a plane (planar features) or a line (edge features) is fitted
/// to them. What cannot be matched is counted by reason.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "odometry/odometry_config.h"
#include "odometry/voxel_map.h"
#include "types/pose.h"

namespace storey {
class ParallelChunks;
}

namespace storey {

struct PlaneMatch {
  Eigen::Vector3d y_imu;    ///< feature point in the IMU frame [m]
  Eigen::Vector3d n_world;  ///< unit normal of the fitted plane
  double d_world;           ///< plane n . x = d [m]
  double sigma;             ///< uncertainty of the point-to-plane distance [m]
};

struct LineMatch {
  Eigen::Vector3d y_imu;    ///< feature point in the IMU frame [m]
  Eigen::Vector3d a_world;  ///< a point of the fitted line [m]
  Eigen::Vector3d u_world;  ///< unit direction of the line
  double sigma;             ///< uncertainty of the point-to-line distance [m]
};

enum class MatchReject : std::uint8_t {
  kTooFewNeighbours = 0,  ///< fewer than `neighbours` map points within max_neighbour_distance
  kNotPlanar,             ///< neighbours do not fit a plane within plane_fit_tolerance
  kNotALine,              ///< neighbours are not elongated enough for a line
  kTooFar,                ///< point farther than max_point_distance from its plane/line
  kOtherSide,             ///< point seen from the other side of the plane than its map points
  kCount
};
const char* toString(MatchReject reason);

struct MatchResult {
  std::vector<PlaneMatch> planes;
  std::vector<LineMatch> lines;
  std::array<std::int64_t, static_cast<std::size_t>(MatchReject::kCount)> rejected{};
};

/// Each match's sigma combines the feature's own uncertainty
/// (config.point_sigma) with the thickness of the fit:
/// sigma^2 = point_sigma^2 + thickness^2, so a poor fit counts less.
/// Associates planar features with `plane_map` and edge features with
/// `edge_map` (both world frame), features given in the IMU frame at T_world_imu.
///
/// Surfaces are seen from one side. When the map points keep their view
/// directions (VoxelMap::insert with a sensor position), the fitted normal is
/// oriented towards the sensors that saw them, and a feature whose own sensor
/// (at `sensor_imu`, the LiDAR's position in the IMU frame) lies behind that
/// plane is rejected (MatchReject::kOtherSide): it belongs to the other face
/// of a slab or wall, a thickness away, not to this plane.
///
/// With `parallel`, the planar features are matched in chunks on its threads
/// (the same result as on one thread).
MatchResult matchFeatures(const std::vector<Eigen::Vector3d>& planes_imu,
                          const std::vector<Eigen::Vector3d>& edges_imu, const Pose& T_world_imu,
                          const VoxelMap& plane_map, const VoxelMap& edge_map,
                          const OdometryConfig& config,
                          const Eigen::Vector3d& sensor_imu = Eigen::Vector3d::Zero(),
                          const ParallelChunks* parallel = nullptr);

}  // namespace storey
