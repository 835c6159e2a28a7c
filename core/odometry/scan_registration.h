#pragma once
/// LiDAR-only registration of a scan to a map (or to another scan), built
/// from the odometry's pieces: the source is voxel-downsampled, the target
/// kept in a VoxelMap, every source point matched to a plane fitted to its
/// nearest target points (matchFeatures), and the pose solved by Ceres with
/// point-to-plane residuals (PointToPlaneFactor, Huber loss) on the 7-value
/// pose block with ImuPoseManifold; association and solve alternate until the
/// pose stops moving. Point-to-point ICP's role, with the odometry's metric.
#include <Eigen/Core>
#include <vector>

#include "odometry/odometry_config.h"
#include "types/pose.h"

namespace storey {

struct ScanRegistrationConfig {
  double source_voxel_size = 0.05;   ///< source points downsampled to this [m]
  VoxelMapConfig target_map{1.0, 30, 0.05, 200.0};  ///< target map (voxel, points, spacing, range)
  double min_range = 0.3;            ///< points closer to the sensor are ignored [m]
  int max_rounds = 30;               ///< association + solve rounds [>= 1]
  int iterations_per_round = 5;      ///< Ceres iterations per round [>= 1]
  int neighbours = 15;               ///< target points per plane fit [>= 3] (several rings)
  double max_neighbour_distance = 1.0;  ///< farthest neighbour of a source point [m]
  double plane_fit_tolerance = 0.05; ///< neighbours within this of their plane [m]
  double max_point_distance = 0.2;   ///< matches farther than this from their plane are dropped [m]
  double point_sigma = 0.05;         ///< uncertainty of a point and its plane [m]
  double huber_width = 0.05;         ///< Huber loss width [m]
  double converged_translation = 1e-4;  ///< stop when a round moves less than this [m] ...
  double converged_rotation = 1e-5;     ///< ... and turns less than this [rad]
};

struct ScanRegistrationResult {
  Pose T_target_source;       ///< maps source points into the target frame
  bool converged = false;     ///< stopped because the pose stopped moving
  int rounds = 0;             ///< association rounds run
  int matches = 0;            ///< point-to-plane matches of the last round
  int source_points = 0;      ///< after downsampling
  double rms_distance = 0.0;  ///< RMS point-to-plane distance of the last round's matches [m]
};

/// Registers `source` to `target` (both in their own sensor frames [m]),
/// starting from `initial` (T_target_source). Non-finite points and points
/// closer than min_range are ignored.
ScanRegistrationResult registerScan(const std::vector<Eigen::Vector3f>& source,
                                    const std::vector<Eigen::Vector3f>& target,
                                    const Pose& initial = Pose(),
                                    const ScanRegistrationConfig& config = {});

}  // namespace storey
