#pragma once
/// Feature points between frames: the LiDAR frame (as extracted), the IMU
/// frame (as the odometry keeps them) and the world (as the local map holds
/// them).
#include <Eigen/Core>
#include <vector>

#include "types/pose.h"

namespace storey {

/// y = T_imu_lidar x for every point x (LiDAR frame, float) [m].
inline std::vector<Eigen::Vector3d> toImuFrame(const std::vector<Eigen::Vector3f>& points_lidar,
                                               const Pose& T_imu_lidar) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points_lidar.size());
  for (const auto& p : points_lidar) out.push_back(T_imu_lidar * p.cast<double>());
  return out;
}

/// T_world_imu y for every point y (IMU frame), as the local map stores them (float) [m].
inline std::vector<Eigen::Vector3f> toWorld(const std::vector<Eigen::Vector3d>& points_imu,
                                            const Pose& T_world_imu) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(points_imu.size());
  for (const auto& p : points_imu) out.push_back((T_world_imu * p).cast<float>());
  return out;
}

}  // namespace storey
