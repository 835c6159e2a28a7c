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
  double time() const { return nsToSeconds(stamp_ns); }  ///< [s]
  bool isFinite() const { return gyro.allFinite() && accel.allFinite(); }
};

}  // namespace storey
