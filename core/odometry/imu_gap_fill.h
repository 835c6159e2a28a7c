#pragma once
/// Filling an IMU dropout (docs/method/imu.md, "Dropouts"). Across a gap the
/// samples on either side are two random phases of a walk's or a trot's
/// gait: their linear interpolation has a mean turn rate and force off by
/// tenths of rad/s and m/s^2, which over a second or two, along a direction
/// the LiDAR cannot see (a corridor's axis), carries the pose metres away.
/// Filled instead at the nominal rate with the motion continued (constant
/// velocity and turn rate), the prediction, the deskew and the IMU factor
/// across the gap all hold a constant-velocity model; the filled samples are
/// marked (ImuSample::filled) and their intervals get the dropout noise, so
/// the LiDAR decides wherever it sees.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "imu/imu_state.h"
#include "types/imu_sample.h"
#include "types/sensor.h"

namespace storey {

/// The longest gap filled [ns].
constexpr std::int64_t kMaxFilledImuGapNs = 10'000'000'000;

/// Whether `after` follows `before` across a dropout: further apart than
/// imuGapThreshold(noise), or after a removed run (ImuSample::after_removed).
bool isImuDropout(const ImuSample& before, const ImuSample& after, const ImuNoise& noise);

/// Mean angular rate and specific force of the measured (not filled)
/// samples of time-ordered `samples` within `span_ns` before `until_ns`
/// (inclusive), or of the last measured one at or before it; zero when
/// there is none.
struct ImuMean {
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< [m/s^2]
};
ImuMean meanOfMeasured(const std::vector<ImuSample>& samples, std::int64_t until_ns,
                       std::int64_t span_ns);

/// The motion the fill continues, at the time the fill starts from.
struct ImuGapMotion {
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();  ///< measured rate to hold [rad/s]
  /// Known state: the specific force is then gravity's alone (constant
  /// velocity) as the IMU turns. Unknown (before the odometry started):
  /// `accel` is held instead.
  bool state_known = false;
  Eigen::Quaterniond q_world_imu = Eigen::Quaterniond::Identity();
  Eigen::Vector3d g_world = Eigen::Vector3d(0.0, 0.0, -9.81);  ///< gravity [m/s^2]
  ImuBias bias;
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< held force when !state_known [m/s^2]
};

/// Samples at the nominal rate (noise.rate_hz) strictly between from_ns and
/// to_ns (the last one at least half a period before to_ns), marked filled:
/// rate `motion.gyro` and the specific force of zero acceleration in the
/// world, -R(t)^T g + b_a with R turning at that rate from
/// motion.q_world_imu at from_ns, or `motion.accel` when the state is not known.
/// None across a gap longer than kMaxFilledImuGapNs (the interpolation and
/// its dropout noise stay): no motion model holds that long.
std::vector<ImuSample> fillImuGap(std::int64_t from_ns, std::int64_t to_ns,
                                  const ImuGapMotion& motion, const ImuNoise& noise);

}  // namespace storey
