#pragma once
/// Prior on the window's oldest state as a whole (odometry.marginalise_pose):
/// its pose, on the pose manifold's tangent [dp, delta] with
/// delta = vec(q q0^-1) (imu/imu_state_blocks.h: q = Exp(delta) q0, a rotation
/// of 2 |delta|), its motion m = [v, b_g, b_a] and gravity's tilt t:
///   r = S [p - p0; vec(q q0^-1); m - m0; t - t0],  S^T S = Lambda (17x17).
/// Made when a state leaves the window (propagateStatePrior) from what the
/// window knew of it: the prior it carried, the information of its own LiDAR
/// residuals and the IMU factor to its successor. Everything but the
/// successor's state is marginalised out (Schur complement), so the
/// successor's position and velocity keep what every scan before them said,
/// and the oldest pose is free (docs/method/odometry.md, "Marginalising the
/// pose").
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "imu/imu_factor.h"
#include "odometry/motion_prior.h"

namespace storey {

using Vector17d = Eigen::Matrix<double, 17, 1>;
using Matrix17d = Eigen::Matrix<double, 17, 17>;

struct StatePrior {
  double pose[7] = {0, 0, 0, 0, 0, 0, 1};         ///< mean T_world_imu [p (3) [m], q x y z w]
  Vector11d motion_tilt = Vector11d::Zero();      ///< mean [v, b_g, b_a, t]
  Matrix17d information = Matrix17d::Identity();  ///< over [dp, delta, v, b_g, b_a, t]
};

/// Blocks: pose (7, the ImuPoseManifold's ambient), motion (9), tilt (2).
class StatePriorFactor final : public ceres::SizedCostFunction<17, 7, 9, 2> {
 public:
  explicit StatePriorFactor(const StatePrior& prior);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d p0_;
  Eigen::Quaterniond q0_inverse_;
  Vector11d motion_tilt0_;
  Eigen::Matrix<double, 17, 17, Eigen::RowMajor> sqrt_information_;
};

/// The prior on state j when state i leaves the window. Variables
/// z = [pose_i (6, tangent), motion_i (9), pose_j (6), motion_j (9), tilt (2)];
/// information from state i's prior (`prior_i`; null when its pose is held
/// fixed, the log's first state: then `motion_prior_i` on [motion_i, tilt]
/// and pose_i known exactly), the IMU factor i -> j (J^T J, whitened) and
/// `lidar_information_i`, state i's LiDAR information over the world tangent
/// [dp, dtheta] (R -> Exp(dtheta) R). pose_i and motion_i are marginalised
/// out, linearised at the current estimates, which are the new mean.
StatePrior propagateStatePrior(const StatePrior* prior_i, const MotionPrior& motion_prior_i,
                               const ImuGravityFactor& factor, const double* pose_i,
                               const double* motion_i, const double* pose_j, const double* motion_j,
                               const double* tilt,
                               const Eigen::Matrix<double, 6, 6>& lidar_information_i);

}  // namespace storey
