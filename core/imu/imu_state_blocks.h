#pragma once
/// How an ImuState is laid out in Ceres parameter blocks, shared by the IMU
/// factor and the LiDAR residuals of the odometry:
///   pose   (7): [p_world_imu x y z [m], q_world_imu x y z w]  (Eigen's
///               coefficient order, Hamilton, unit norm)
///   motion (9): [v_world_imu x y z [m/s], bias_gyro x y z [rad/s],
///                bias_accel x y z [m/s^2]]
/// Two blocks rather than one 16-vector: the many LiDAR residuals of a scan
/// touch only the pose, so their Jacobians stay 7 wide and Ceres' sparsity
/// sees that velocity and biases are linked only by IMU factors.
///
/// Pose manifold: ceres::ProductManifold<EuclideanManifold<3>,
/// EigenQuaternionManifold>, tangent [dp (3) [m], delta (3)], with
/// p + dp and q <- [sin|delta| delta/|delta|, cos|delta|] * q: a rotation
/// of 2 |delta| rad about the world axis delta (left perturbation; the
/// rotation vector is 2 delta).
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/product_manifold.h>

#include <cstdint>

#include "imu/imu_state.h"

namespace storey {

using ImuPoseManifold =
    ceres::ProductManifold<ceres::EuclideanManifold<3>, ceres::EigenQuaternionManifold>;

struct ImuStateBlocks {
  static constexpr int kPoseSize = 7;  ///< ambient size of the pose block
  static constexpr int kPoseTangentSize = 6;
  static constexpr int kMotionSize = 9;  ///< size of the velocity + biases block

  double pose[kPoseSize] = {0, 0, 0, 0, 0, 0, 1};  ///< [p (3) [m], q x y z w]
  double motion[kMotionSize] = {};  ///< [v (3) [m/s], bg (3) [rad/s], ba (3) [m/s^2]]

  static ImuStateBlocks fromState(const ImuState& state);
  /// Back to a state (the quaternion is normalised); stamp_ns is not stored in the blocks.
  ImuState toState(std::int64_t stamp_ns) const;
};

/// Adds blocks.pose (with a new ImuPoseManifold, owned by the problem: keep
/// Problem::Options::manifold_ownership at its default TAKE_OWNERSHIP) and
/// blocks.motion to `problem`. The blocks must not move while the problem
/// lives (keep states in a std::deque or behind pointers, not in a growing
/// std::vector). Blocks already in the problem are left as they are.
void addImuStateBlocks(ceres::Problem& problem, ImuStateBlocks& blocks);

}  // namespace storey
