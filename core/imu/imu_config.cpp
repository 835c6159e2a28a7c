#include "imu/imu_config.h"

#include <cmath>
#include <string>

#include "common/error.h"

namespace storey {
namespace {

void require(bool ok, const char* key, const char* rule) {
  if (!ok) throw Error(std::string("imu config: ") + key + " must be " + rule);
}

bool positive(double x) {
  return std::isfinite(x) && x > 0.0;
}

}  // namespace

void ImuInitConfig::validate() const {
  require(positive(still_window), "still_window", "> 0 s");
  require(positive(max_gyro_std), "max_gyro_std", "> 0 rad/s");
  require(positive(max_accel_std), "max_accel_std", "> 0 m/s^2");
  require(std::isfinite(noise_margin) && noise_margin >= 1.0, "noise_margin", ">= 1");
  require(positive(max_gyro_bias), "max_gyro_bias", "> 0 rad/s");
  require(positive(max_gravity_error), "max_gravity_error", "> 0 m/s^2");
  require(positive(motion_window), "motion_window", "> 0 s");
  require(motion_min_scans >= 3, "motion_min_scans", ">= 3");
}

void ImuPreintegrationConfig::validate() const {
  require(positive(repropagate_gyro_bias_change), "repropagate_gyro_bias_change", "> 0 rad/s");
  require(positive(repropagate_accel_bias_change), "repropagate_accel_bias_change", "> 0 m/s^2");
}

}  // namespace storey
