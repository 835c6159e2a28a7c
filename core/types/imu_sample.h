#pragma once
/// One IMU measurement in the IMU frame.
#include <Eigen/Core>
#include <cstdint>

#include "common/time.h"

namespace storey {

struct ImuSample {
  std::int64_t stamp_ns = 0;                        ///< sensor time [ns]
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< angular rate [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< specific force [m/s^2], includes gravity
  /// Samples before this one were removed (a saturated run, io/imu_guard.h):
  /// the interval from the previous sample is a dropout whatever its length.
  bool after_removed = false;
  /// Not measured: synthesised across a dropout (odometry/imu_gap_fill.h),
  /// the motion continued at constant velocity and turn rate. The intervals
  /// to and from it are dropouts whatever their length.
  bool filled = false;
  double time() const { return nsToSeconds(stamp_ns); }  ///< [s]
  bool isFinite() const { return gyro.allFinite() && accel.allFinite(); }
};

}  // namespace storey
