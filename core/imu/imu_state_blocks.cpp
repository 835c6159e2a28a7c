#include "imu/imu_state_blocks.h"

#include <Eigen/Geometry>

namespace storey {

ImuStateBlocks ImuStateBlocks::fromState(const ImuState& state) {
  ImuStateBlocks b;
  Eigen::Map<Eigen::Vector3d>(b.pose) = state.T_world_imu.translation();
  Eigen::Map<Eigen::Quaterniond>(b.pose + 3) = state.T_world_imu.rotation();
  Eigen::Map<Eigen::Vector3d>(b.motion) = state.v_world_imu;
  Eigen::Map<Eigen::Vector3d>(b.motion + 3) = state.bias.gyro;
  Eigen::Map<Eigen::Vector3d>(b.motion + 6) = state.bias.accel;
  return b;
}

ImuState ImuStateBlocks::toState(std::int64_t stamp_ns) const {
  ImuState s;
  s.stamp_ns = stamp_ns;
  s.T_world_imu = Pose(Eigen::Quaterniond(Eigen::Map<const Eigen::Quaterniond>(pose + 3)),
                       Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(pose)));
  s.v_world_imu = Eigen::Map<const Eigen::Vector3d>(motion);
  s.bias.gyro = Eigen::Map<const Eigen::Vector3d>(motion + 3);
  s.bias.accel = Eigen::Map<const Eigen::Vector3d>(motion + 6);
  return s;
}

void addImuStateBlocks(ceres::Problem& problem, ImuStateBlocks& blocks) {
  if (!problem.HasParameterBlock(blocks.pose)) {
    problem.AddParameterBlock(blocks.pose, ImuStateBlocks::kPoseSize, new ImuPoseManifold);
  }
  if (!problem.HasParameterBlock(blocks.motion)) {
    problem.AddParameterBlock(blocks.motion, ImuStateBlocks::kMotionSize);
  }
}

}  // namespace storey
