// The named presets of the spec's sensor and robot parts (building_spec.h):
// IMU grades from datasheets, robot motions from published gait figures.
// docs/simulator.md ("IMU grades", "Handheld walking") lists the same figures.
#include <cmath>
#include <initializer_list>
#include <string>

#include "common/error.h"
#include "sim/building_spec.h"

namespace storey::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kStandardGravity = 9.80665;  ///< datasheets' g [m/s^2]
constexpr double kMicroG = 1e-6 * kStandardGravity;
/// The bias random walk reaches the in-run drift figure after this long [s]
/// (datasheets give a bias stability, not a random-walk density).
constexpr double kDriftWindowS = 100.0;

/// The value of `values` whose toString() is `name`; storey::Error naming the choices.
template <typename E>
E fromName(const std::string& name, std::initializer_list<E> values, const char* choices) {
  for (E value : values)
    if (name == toString(value)) return value;
  throw Error(std::string("must be ") + choices + "; got '" + name + "'");
}

}  // namespace

const char* toString(ImuGrade grade) {
  switch (grade) {
    case ImuGrade::kTactical:
      return "tactical";
    case ImuGrade::kConsumer:
      return "consumer";
  }
  return "tactical";
}

ImuGrade imuGradeFromString(const std::string& name) {
  return fromName(name, {ImuGrade::kTactical, ImuGrade::kConsumer}, "tactical, consumer or custom");
}

ImuRateRange imuGradeRates(ImuGrade grade) {
  switch (grade) {
    case ImuGrade::kTactical:
      return {200.0, 400.0};
    case ImuGrade::kConsumer:
      return {100.0, 200.0};
  }
  return {};
}

ImuSpec imuGrade(ImuGrade grade, double rate_hz) {
  const ImuRateRange rates = imuGradeRates(grade);
  if (!(rate_hz >= rates.min_hz && rate_hz <= rates.max_hz)) {
    throw Error(std::string("IMU grade ") + toString(grade) + ": rate " + std::to_string(rate_hz) +
                " Hz is outside its range [" + std::to_string(rates.min_hz) + ", " +
                std::to_string(rates.max_hz) + "] Hz");
  }
  ImuSpec imu;
  imu.grade = grade;
  imu.rate = rate_hz;
  switch (grade) {
    case ImuGrade::kTactical:
      // Xsens MTi 100-series datasheet, MTi-300: gyroscope noise density
      // 0.01 deg/s/sqrt(Hz), in-run bias stability 10 deg/h; accelerometer
      // noise density 60 ug/sqrt(Hz), in-run bias stability 15 ug; orientation
      // roll/pitch 0.3 deg (dynamic), yaw 1 deg.
      imu.gyro_noise_density = 0.01 * kDeg;
      imu.accel_noise_density = 60.0 * kMicroG;
      imu.gyro_random_walk = 10.0 * kDeg / 3600.0 / std::sqrt(kDriftWindowS);
      imu.accel_random_walk = 15.0 * kMicroG / std::sqrt(kDriftWindowS);
      // A factory-calibrated unit's residual turn-on bias (not a datasheet figure).
      imu.gyro_bias = Eigen::Vector3d(0.002, -0.0015, 0.001);
      imu.accel_bias = Eigen::Vector3d(0.03, -0.02, 0.04);
      imu.orientation_sigma = Eigen::Vector3d(0.3, 0.3, 1.0) * kDeg;
      break;
    case ImuGrade::kConsumer:
      // Bosch BMI088 datasheet (BST-BMI088-DS001): gyroscope output noise
      // density 0.014 deg/s/sqrt(Hz), zero-rate offset +-1 deg/s, offset drift
      // over temperature 0.015 deg/s/K; accelerometer output noise density
      // 175 ug/sqrt(Hz), zero-g offset +-20 mg, offset drift 0.2 mg/K. Its
      // in-run drift is the temperature's: 1 K of warming (the datasheet's
      // 2 deg/h gyro bias stability holds at a constant temperature only).
      imu.gyro_noise_density = 0.014 * kDeg;
      imu.accel_noise_density = 175.0 * kMicroG;
      imu.gyro_random_walk = 0.015 * kDeg / std::sqrt(kDriftWindowS);
      imu.accel_random_walk = 200.0 * kMicroG / std::sqrt(kDriftWindowS);
      // Turn-on offsets within the typical ones (0.46, -0.34, 0.29 deg/s; 12, -9, 15 mg).
      imu.gyro_bias = Eigen::Vector3d(0.008, -0.006, 0.005);
      imu.accel_bias = Eigen::Vector3d(0.12, -0.09, 0.15);
      // No orientation output on the chip: what a host AHRS without
      // magnetometer might state (an assumption).
      imu.orientation_sigma = Eigen::Vector3d(1.0, 1.0, 5.0) * kDeg;
      break;
  }
  return imu;
}

const char* toString(RobotMotion motion) {
  switch (motion) {
    case RobotMotion::kLegged:
      return "legged";
    case RobotMotion::kHandheld:
      return "handheld";
  }
  return "legged";
}

RobotMotion robotMotionFromString(const std::string& name) {
  return fromName(name, {RobotMotion::kLegged, RobotMotion::kHandheld}, "legged or handheld");
}

RobotSpec robotForMotion(RobotMotion motion) {
  RobotSpec robot;
  robot.motion = motion;
  if (motion == RobotMotion::kHandheld) {
    // A surveyor's pace (below the 1.3-1.4 m/s people choose unburdened),
    // about 0.5 m/s along the stairs, turning at up to 90 deg/s,
    // the sensors held at chest height. HandheldGaitSpec's defaults are the gait.
    robot.walk_speed = 1.0;
    robot.stair_speed = 0.5;
    robot.max_accel = 0.8;
    robot.max_lateral_accel = 1.0;
    robot.max_yaw_rate = 90.0 * kDeg;
    robot.body_height = 1.2;
  }
  return robot;
}

}  // namespace storey::sim
