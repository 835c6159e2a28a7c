#include "odometry/odometry_config.h"

#include <string>
#include <utility>

#include "common/error.h"

namespace storey {

void OdometryConfig::validate() const {
  const OdometryConfig& o = *this;
  requireKey(o.window_size >= 2, "odometry.window_size", "must be >= 2");
  requireKey(o.matching_rounds >= 1, "odometry.matching_rounds", "must be >= 1");
  requireKey(o.threads >= 0, "odometry.threads", "must be >= 0 (0: every core)");
  requireKey(o.max_matched_planes >= 0, "odometry.max_matched_planes", "must be >= 0");
  requireKey(o.max_iterations >= 1, "odometry.max_iterations", "must be >= 1");
  requireKey(o.neighbours >= 3 && o.neighbours <= VoxelMap::kMaxNeighbours, "odometry.neighbours",
             "must be within [3, 16]");
  requireKey(o.plane_fit_min_inliers == 0 ||
                 (o.plane_fit_min_inliers >= 3 && o.plane_fit_min_inliers <= o.neighbours),
             "odometry.plane_fit_min_inliers", "must be 0 (off) or within [3, neighbours]");
  for (const auto& [key, value] :
       {std::pair<const char*, double>{"odometry.max_neighbour_distance", o.max_neighbour_distance},
        {"odometry.plane_fit_tolerance", o.plane_fit_tolerance},
        {"odometry.line_eigen_ratio", o.line_eigen_ratio},
        {"odometry.max_point_distance", o.max_point_distance},
        {"odometry.point_sigma", o.point_sigma},
        {"odometry.huber_threshold", o.huber_threshold},
        {"odometry.degenerate_translation_std", o.degenerate_translation_std},
        {"odometry.degenerate_rotation_std", o.degenerate_rotation_std},
        {"odometry.max_scan_gap", o.max_scan_gap},
        {"odometry.prior_velocity_sigma", o.prior_velocity_sigma},
        {"odometry.prior_gyro_bias_sigma", o.prior_gyro_bias_sigma},
        {"odometry.prior_accel_bias_sigma", o.prior_accel_bias_sigma},
        {"odometry.pose_sigma_translation", o.pose_sigma_translation},
        {"odometry.pose_sigma_rotation", o.pose_sigma_rotation},
        {"odometry.local_map.voxel_size", o.local_map.voxel_size},
        {"odometry.local_map.max_range", o.local_map.max_range},
        {"odometry.imu_init.still_window", o.imu_init.still_window},
        {"odometry.imu_init.max_gyro_std", o.imu_init.max_gyro_std},
        {"odometry.imu_init.max_accel_std", o.imu_init.max_accel_std},
        {"odometry.features.edge_threshold", o.features.edge_threshold},
        {"odometry.features.occlusion_gap", o.features.occlusion_gap}}) {
    requireKey(value > 0.0, key, "must be positive");
  }
  requireKey(o.features.neighbours >= 2, "odometry.features.neighbours", "must be >= 2");
  requireKey(o.features.sectors >= 1, "odometry.features.sectors", "must be >= 1");
  requireKey(o.features.plane_threshold < o.features.edge_threshold,
             "odometry.features.plane_threshold",
             "must be below 'odometry.features.edge_threshold'");
  requireKey(o.local_map.max_points_per_voxel >= 1, "odometry.local_map.max_points_per_voxel",
             "must be >= 1");
  requireKey(o.max_neighbour_distance <= o.local_map.voxel_size, "odometry.max_neighbour_distance",
             "must not exceed 'odometry.local_map.voxel_size' (neighbours are searched in the 27 "
             "voxels around a point)");
  requireKey(o.imu_init.noise_margin >= 1.0, "odometry.imu_init.noise_margin", "must be >= 1");
  try {
    o.imu_init.validate();
  } catch (const Error& e) {
    throw Error(std::string("in section 'odometry.imu_init': ") + e.what());
  }
  try {
    o.preintegration.validate();
  } catch (const Error& e) {
    throw Error(std::string("in section 'odometry.preintegration': ") + e.what());
  }
}

}  // namespace storey
