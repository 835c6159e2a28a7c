#pragma once
/// The IMU's navigation state and biases, as estimated by the odometry.
#include <Eigen/Core>
#include <cstdint>

#include "types/pose.h"

namespace storey {

/// Additive sensor biases: measured = true + bias (+ noise).
struct ImuBias {
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< gyroscope bias [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< accelerometer bias [m/s^2]
};

/// State of the IMU frame at one time. World frame: z up, gravity (0, 0, -g).
struct ImuState {
  std::int64_t stamp_ns = 0;  ///< time of the state [ns]
  Pose T_world_imu;           ///< pose of the IMU in the world
  Eigen::Vector3d v_world_imu =
      Eigen::Vector3d::Zero();  ///< velocity of the IMU in the world [m/s]
  ImuBias bias;                 ///< biases at that time
};

/// Gravity vector of the world frame for a gravity magnitude g [m/s^2]: (0, 0, -g).
inline Eigen::Vector3d gravityWorld(double g) {
  return Eigen::Vector3d(0.0, 0.0, -g);
}

}  // namespace storey
