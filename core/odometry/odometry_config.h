#pragma once
/// Parameters of the LiDAR-inertial odometry (front end), defaults in the
/// struct, units beside each field.
#include "imu/imu_config.h"
#include "odometry/features.h"
#include "odometry/voxel_map.h"

namespace storey {

struct OdometryConfig {
  FeatureConfig features;
  VoxelMapConfig local_map;
  ImuInitConfig imu_init;
  ImuPreintegrationConfig preintegration;

  int window_size = 3;      ///< states optimised together (oldest held fixed) [>= 2]
  int matching_rounds = 2;  ///< feature association rounds per scan [>= 1]
  int max_iterations = 4;   ///< Ceres iterations per round [>= 1]
  int threads = 0;          ///< threads for a scan's features and matching (0: every core; 1: the
                            ///< odometry's own thread); the results are the same [>= 0]
  int max_matched_planes = 1500;        ///< planar features of a scan matched to the map: more are
                                        ///< thinned evenly (all still enter the map); 0: all [>= 0]
  int neighbours = 8;                   ///< map points used to fit a plane or a line [>= 3]
                                        ///< (5 fitted false planes across stair steps: odometry.md)
  double max_neighbour_distance = 0.5;  ///< farthest map neighbour of a feature [m]
  double plane_fit_tolerance = 0.05;    ///< every neighbour within this of its plane [m]
  int plane_fit_min_inliers = 0;        ///< 0: every neighbour must fit the plane; k: the
                                        ///< neighbourhood's largest face, of at least k
                                        ///< neighbours (a stair's tread, not tread and riser
                                        ///< together: fitPlaneLargestFace) [0 or 3..neighbours]
  double line_eigen_ratio = 3.0;  ///< a line's neighbours: largest eigenvalue > ratio x second [-]
  double max_point_distance = 1.0;  ///< matches farther than this from their plane/line
                                    ///< at the predicted pose are rejected [m]
  double point_sigma = 0.03;       ///< uncertainty of a feature point and its fitted plane/line [m]
                                   ///< (a VLP-16-class LiDAR's range accuracy)
  double huber_threshold = 1.345;  ///< robust (Huber) loss on the whitened residual |r| / sigma:
                                   ///< quadratic up to this many standard deviations [-]
  double degenerate_translation_std = 0.02;  ///< LiDAR-only std above which a direction is
                                             ///< reported degenerate [m]
  double degenerate_rotation_std = 0.005;    ///< same for rotations [rad]
  double prior_velocity_sigma = 0.01;        ///< initial velocity uncertainty (still start) [m/s]
  double prior_gyro_bias_sigma = 1e-3;       ///< initial gyro bias uncertainty [rad/s]
  double prior_accel_bias_sigma = 0.05;      ///< initial accel bias uncertainty [m/s^2]
  double pose_sigma_translation = 0.02;      ///< accuracy of a registered pose, used when the
                                             ///< oldest state leaves the window [m]
  double pose_sigma_rotation = 0.005;        ///< same for its rotation [rad]
  bool marginalise_pose = false;  ///< a state leaving the window passes a prior on the next
                                  ///< one's pose, motion and tilt, with its own LiDAR
                                  ///< information (the oldest pose is free); false: the
                                  ///< oldest pose is held fixed and pose_sigma_* stand in
  double max_scan_gap =
      0.5;  ///< a longer time between scans is logged (the reader warns: faults) [s]

  /// Checks value ranges; throws storey::Error naming the key (under `odometry.`) at fault.
  void validate() const;
};

}  // namespace storey
