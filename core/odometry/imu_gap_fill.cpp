#include "odometry/imu_gap_fill.h"

#include <algorithm>

#include "imu/so3.h"

namespace storey {

bool isImuDropout(const ImuSample& before, const ImuSample& after, const ImuNoise& noise) {
  return after.after_removed ||
         after.stamp_ns - before.stamp_ns > secondsToNs(imuGapThreshold(noise));
}

ImuMean meanOfMeasured(const std::vector<ImuSample>& samples, std::int64_t until_ns,
                       std::int64_t span_ns) {
  ImuMean mean;
  const auto after =
      std::upper_bound(samples.begin(), samples.end(), until_ns,
                       [](std::int64_t t, const ImuSample& s) { return t < s.stamp_ns; });
  int n = 0;
  for (auto it = std::make_reverse_iterator(after); it != samples.rend(); ++it) {
    if (n > 0 && it->stamp_ns < until_ns - span_ns) break;
    if (it->filled) continue;
    mean.gyro += it->gyro;
    mean.accel += it->accel;
    ++n;
  }
  if (n > 0) {
    mean.gyro /= n;
    mean.accel /= n;
  }
  return mean;
}

std::vector<ImuSample> fillImuGap(std::int64_t from_ns, std::int64_t to_ns,
                                  const ImuGapMotion& motion, const ImuNoise& noise) {
  std::vector<ImuSample> out;
  if (to_ns - from_ns > kMaxFilledImuGapNs) return out;
  const std::int64_t period_ns = std::max<std::int64_t>(secondsToNs(1.0 / noise.rate_hz), 1);
  const std::int64_t last_ns = to_ns - period_ns / 2;
  const Eigen::Vector3d rate = motion.gyro - motion.bias.gyro;
  for (std::int64_t t = from_ns + period_ns; t < last_ns; t += period_ns) {
    ImuSample s;
    s.stamp_ns = t;
    s.filled = true;
    s.gyro = motion.gyro;
    if (motion.state_known) {
      // R(t) = R(from) Exp(rate tau): gravity seen from the turned IMU.
      const double tau = nsToSeconds(t - from_ns);
      const Eigen::Quaterniond q_world_imu = motion.q_world_imu * so3::expQuaternion(rate * tau);
      s.accel = q_world_imu.conjugate() * (-motion.g_world) + motion.bias.accel;
    } else {
      s.accel = motion.accel;
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace storey
