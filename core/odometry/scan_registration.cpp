#include "odometry/scan_registration.h"

#include <ceres/ceres.h>

#include <cmath>

#include "imu/imu_state_blocks.h"
#include "odometry/features.h"
#include "odometry/lidar_factors.h"
#include "odometry/scan_matcher.h"
#include "odometry/voxel_map.h"

namespace storey {
namespace {

std::vector<Eigen::Vector3f> usable(const std::vector<Eigen::Vector3f>& points, double min_range) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size());
  for (const auto& p : points) {
    if (p.allFinite() && p.norm() >= min_range) out.push_back(p);
  }
  return out;
}

Pose poseOf(const double* block) {
  return Pose(Eigen::Quaterniond(block[6], block[3], block[4], block[5]),
              Eigen::Vector3d(block[0], block[1], block[2]));
}

}  // namespace

ScanRegistrationResult registerScan(const std::vector<Eigen::Vector3f>& source,
                                    const std::vector<Eigen::Vector3f>& target, const Pose& initial,
                                    const ScanRegistrationConfig& config) {
  ScanRegistrationResult result;
  result.T_target_source = initial;
  VoxelMap target_map(config.target_map);
  target_map.insert(usable(target, config.min_range));
  const VoxelMap no_edges(config.target_map);
  std::vector<Eigen::Vector3d> source_points;
  for (const auto& p : voxelDownsample(usable(source, config.min_range), config.source_voxel_size)) {
    source_points.push_back(p.cast<double>());
  }
  result.source_points = static_cast<int>(source_points.size());
  if (source_points.empty() || target_map.empty()) return result;

  OdometryConfig matching;
  matching.neighbours = config.neighbours;
  matching.max_neighbour_distance = config.max_neighbour_distance;
  matching.plane_fit_tolerance = config.plane_fit_tolerance;
  matching.max_point_distance = config.max_point_distance;
  matching.point_sigma = config.point_sigma;

  double pose[7];
  for (int round = 0; round < config.max_rounds; ++round) {
    const Pose before = result.T_target_source;
    const Eigen::Quaterniond& q = before.rotation();
    const Eigen::Vector3d& t = before.translation();
    double init[7] = {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
    std::copy(init, init + 7, pose);

    const MatchResult matches = matchFeatures(source_points, {}, before, target_map, no_edges, matching);
    result.rounds = round + 1;
    result.matches = static_cast<int>(matches.planes.size());
    if (matches.planes.size() < 6) break;

    ceres::Problem problem;
    problem.AddParameterBlock(pose, 7, new ImuPoseManifold());
    for (const auto& m : matches.planes) {
      // Huber on the whitened residual: quadratic up to huber_width / sigma.
      problem.AddResidualBlock(new PointToPlaneFactor(m.y_imu, m.n_world, m.d_world, 1.0 / m.sigma),
                               new ceres::HuberLoss(config.huber_width / m.sigma), pose);
    }
    ceres::Solver::Options options;
    options.max_num_iterations = config.iterations_per_round;
    options.linear_solver_type = ceres::DENSE_QR;
    options.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    result.T_target_source = poseOf(pose);

    double sum = 0.0;
    for (const auto& m : matches.planes) {
      const double distance = m.n_world.dot(result.T_target_source * m.y_imu) - m.d_world;
      sum += distance * distance;
    }
    result.rms_distance = std::sqrt(sum / static_cast<double>(matches.planes.size()));
    const Pose step = before.inverse() * result.T_target_source;
    if (step.translation().norm() < config.converged_translation &&
        Eigen::AngleAxisd(step.rotation()).angle() < config.converged_rotation) {
      result.converged = true;
      break;
    }
  }
  return result;
}

}  // namespace storey
