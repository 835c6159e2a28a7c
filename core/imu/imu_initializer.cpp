#include "imu/imu_initializer.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/format.h"

namespace storey {
Eigen::Quaterniond gravityAlignedRotation(const Eigen::Vector3d& up_imu) {
  const Eigen::Vector3d u = up_imu.normalized();
  const double pitch = std::atan2(-u.x(), std::hypot(u.y(), u.z()));
  const double roll = std::atan2(u.y(), u.z());
  return Eigen::Quaterniond(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
}

ImuInitResult initializeImuFromStill(const std::vector<ImuSample>& samples, const ImuNoise& noise,
                                     const ImuInitConfig& config) {
  config.validate();
  const std::string window_text = significantText(config.still_window) + " s";
  if (samples.size() < 2) {
    throw Error("IMU initialisation needs the first " + window_text +
                " of IMU data at rest, but the log has " + std::to_string(samples.size()) +
                " IMU samples");
  }
  const std::int64_t t0 = samples.front().stamp_ns;
  const std::int64_t t_end = t0 + secondsToNs(config.still_window);
  if (samples.back().stamp_ns < t_end) {
    throw Error("IMU initialisation needs the first " + window_text +
                " of IMU data at rest, but the IMU data last only " +
                significantText(nsToSeconds(samples.back().stamp_ns - t0)) + " s");
  }
  const auto end =
      std::upper_bound(samples.begin(), samples.end(), t_end,
                       [](std::int64_t t, const ImuSample& s) { return t < s.stamp_ns; });

  ImuInitStats stats;
  stats.samples = static_cast<std::size_t>(end - samples.begin());
  stats.window_start_ns = t0;
  stats.window_end_ns = (end - 1)->stamp_ns;
  Eigen::Vector3d mean_gyro = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_accel = Eigen::Vector3d::Zero();
  for (auto it = samples.begin(); it != end; ++it) {
    if (!it->isFinite()) {
      throw Error("IMU initialisation: sample at " + significantText(it->time(), 12) +
                  " s is not finite");
    }
    mean_gyro += it->gyro;
    mean_accel += it->accel;
  }
  const double n = static_cast<double>(stats.samples);
  mean_gyro /= n;
  mean_accel /= n;
  double gyro_var = 0.0;
  double accel_var = 0.0;
  for (auto it = samples.begin(); it != end; ++it) {
    gyro_var += (it->gyro - mean_gyro).squaredNorm();
    accel_var += (it->accel - mean_accel).squaredNorm();
  }
  stats.gyro_std = std::sqrt(gyro_var / n);
  stats.accel_std = std::sqrt(accel_var / n);
  stats.mean_accel_norm = mean_accel.norm();

  // White noise of density s sampled at rate f has a per-axis std of s sqrt(f).
  const double rate = (n - 1.0) / std::max(1e-9, nsToSeconds(stats.window_end_ns - t0));
  stats.gyro_std_limit = std::max(
      config.max_gyro_std, config.noise_margin * noise.gyro_noise_density * std::sqrt(3.0 * rate));
  stats.accel_std_limit =
      std::max(config.max_accel_std,
               config.noise_margin * noise.accel_noise_density * std::sqrt(3.0 * rate));

  const std::string head = "the first " + window_text + " of IMU data are not still: ";
  const std::string fix =
      "; Storey initialises gravity and the gyro bias from a still start: record the first " +
      window_text + " with the sensor at rest (limits: odometry.imu_init in the config)";
  if (stats.gyro_std > stats.gyro_std_limit) {
    throw Error(head + "gyro std " + significantText(stats.gyro_std) + " rad/s > " +
                significantText(stats.gyro_std_limit) + " rad/s" + fix);
  }
  if (stats.accel_std > stats.accel_std_limit) {
    throw Error(head + "accel std " + significantText(stats.accel_std) + " m/s^2 > " +
                significantText(stats.accel_std_limit) + " m/s^2" + fix);
  }
  if (mean_gyro.norm() > config.max_gyro_bias) {
    throw Error(head + "mean gyro " + significantText(mean_gyro.norm()) + " rad/s > " +
                significantText(config.max_gyro_bias) +
                " rad/s (a steady rotation, or a gyro bias above "
                "max_gyro_bias)" +
                fix);
  }
  if (std::abs(stats.mean_accel_norm - noise.gravity) > config.max_gravity_error) {
    throw Error("IMU initialisation: the mean specific force in the first " + window_text + " is " +
                significantText(stats.mean_accel_norm) + " m/s^2, not gravity (" +
                significantText(noise.gravity) + " +- " +
                significantText(config.max_gravity_error) +
                " m/s^2): the sensor is accelerating, or its accelerations are not in m/s^2 "
                "(in g?)" +
                fix);
  }

  const Eigen::Vector3d up = mean_accel / stats.mean_accel_norm;
  stats.up_imu = up;
  ImuInitResult result;
  result.stats = stats;
  result.state.stamp_ns = stats.window_end_ns;
  result.state.T_world_imu = Pose(gravityAlignedRotation(up), Eigen::Vector3d::Zero());
  result.state.v_world_imu.setZero();
  result.state.bias.gyro = mean_gyro;
  result.state.bias.accel = config.accel_bias_along_gravity
                                ? Eigen::Vector3d((stats.mean_accel_norm - noise.gravity) * up)
                                : Eigen::Vector3d::Zero();
  return result;
}

}  // namespace storey
