// IMU grades: the datasheet figures, and a simulated static IMU whose noise
// and bias walk have the spread the grade states.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "sim/imu_simulator.h"
#include "sim/world.h"

namespace storey::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kMicroG = 9.80665e-6;

TEST(SimImu, GradesCarryTheirDatasheetFigures) {
  // Xsens MTi-300: 0.01 deg/s/sqrt(Hz), 60 ug/sqrt(Hz); bias stability 10 deg/h, 15 ug.
  const ImuSpec tactical = imuGrade(ImuGrade::kTactical, 400.0);
  ASSERT_TRUE(tactical.grade);
  EXPECT_EQ(*tactical.grade, ImuGrade::kTactical);
  EXPECT_DOUBLE_EQ(tactical.rate, 400.0);
  EXPECT_NEAR(tactical.gyro_noise_density, 0.01 * kDeg, 1e-12);
  EXPECT_NEAR(tactical.accel_noise_density, 60 * kMicroG, 1e-12);
  EXPECT_NEAR(tactical.gyro_random_walk * std::sqrt(100.0), 10 * kDeg / 3600, 1e-12);
  EXPECT_NEAR(tactical.accel_random_walk * std::sqrt(100.0), 15 * kMicroG, 1e-12);
  // Bosch BMI088: 0.014 deg/s/sqrt(Hz), 175 ug/sqrt(Hz); drift 0.015 deg/s/K, 0.2 mg/K.
  const ImuSpec consumer = imuGrade(ImuGrade::kConsumer, 100.0);
  EXPECT_EQ(*consumer.grade, ImuGrade::kConsumer);
  EXPECT_NEAR(consumer.gyro_noise_density, 0.014 * kDeg, 1e-12);
  EXPECT_NEAR(consumer.accel_noise_density, 175 * kMicroG, 1e-12);
  EXPECT_NEAR(consumer.gyro_random_walk * std::sqrt(100.0), 0.015 * kDeg, 1e-12);
  EXPECT_NEAR(consumer.accel_random_walk * std::sqrt(100.0), 200 * kMicroG, 1e-12);
  // Consumer is worse on every count.
  EXPECT_GT(consumer.gyro_noise_density, tactical.gyro_noise_density);
  EXPECT_GT(consumer.accel_noise_density, tactical.accel_noise_density);
  EXPECT_GT(consumer.gyro_random_walk, tactical.gyro_random_walk);
  EXPECT_GT(consumer.accel_random_walk, tactical.accel_random_walk);
  EXPECT_GT(consumer.gyro_bias.norm(), tactical.gyro_bias.norm());
  EXPECT_GT(consumer.accel_bias.norm(), tactical.accel_bias.norm());
  // Turn-on biases within the datasheets' typical offsets (BMI088: 1 deg/s, 20 mg).
  EXPECT_LT(consumer.gyro_bias.cwiseAbs().maxCoeff(), 1.0 * kDeg);
  EXPECT_LT(consumer.accel_bias.cwiseAbs().maxCoeff(), 20'000 * kMicroG);
  // Rates.
  EXPECT_DOUBLE_EQ(imuGradeRates(ImuGrade::kTactical).min_hz, 200.0);
  EXPECT_DOUBLE_EQ(imuGradeRates(ImuGrade::kTactical).max_hz, 400.0);
  EXPECT_DOUBLE_EQ(imuGradeRates(ImuGrade::kConsumer).min_hz, 100.0);
  EXPECT_DOUBLE_EQ(imuGradeRates(ImuGrade::kConsumer).max_hz, 200.0);
  EXPECT_THROW(imuGrade(ImuGrade::kTactical, 100.0), Error);
  EXPECT_THROW(imuGrade(ImuGrade::kConsumer, 400.0), Error);
  // Names.
  for (ImuGrade g : {ImuGrade::kTactical, ImuGrade::kConsumer})
    EXPECT_EQ(imuGradeFromString(toString(g)), g);
  EXPECT_THROW(imuGradeFromString("navigation"), Error);
}

/// A static IMU of each grade, mounted tilted with a lever arm: the white
/// noise has the spread density * sqrt(rate), the bias walks with
/// random_walk * sqrt(T) over T.
TEST(SimImu, StaticImuNoiseAndBiasWalkMatchEachGrade) {
  for (const auto& [grade, rate] :
       {std::pair{ImuGrade::kTactical, 400.0}, std::pair{ImuGrade::kConsumer, 100.0}}) {
    SCOPED_TRACE(toString(grade));
    BuildingSpec spec = loadBuildingSpec("tiny");
    spec.robot.still_time = 60.0;
    spec.sensors.imu = imuGrade(grade, rate);
    spec.sensors.T_body_imu =
        Pose(Eigen::Quaterniond(Eigen::AngleAxisd(2.5, Eigen::Vector3d(0.3, -1, 0.2).normalized())),
             Eigen::Vector3d(0.3, 0.0, 0.0));
    const ImuSpec& imu = spec.sensors.imu;
    const World world = makeWorld(spec);
    ASSERT_GE(world.trajectory.stillTime(), 60.0);

    // White noise: the spread of the static samples around their mean, per
    // 1 s window (the bias hardly moves in one), pooled over windows and axes.
    const ImuSimulation still = simulateImu(world.trajectory, spec.sensors, 59.0, false, 11);
    const int per_window = static_cast<int>(rate);
    double gyro_ss = 0.0, accel_ss = 0.0;
    int dof = 0;
    for (std::size_t w = 0; w + per_window <= still.samples.size(); w += per_window) {
      Eigen::Vector3d gyro_mean = Eigen::Vector3d::Zero(), accel_mean = Eigen::Vector3d::Zero();
      for (int k = 0; k < per_window; ++k) {
        gyro_mean += still.samples[w + k].gyro / per_window;
        accel_mean += still.samples[w + k].accel / per_window;
      }
      for (int k = 0; k < per_window; ++k) {
        gyro_ss += (still.samples[w + k].gyro - gyro_mean).squaredNorm();
        accel_ss += (still.samples[w + k].accel - accel_mean).squaredNorm();
      }
      dof += 3 * (per_window - 1);
    }
    ASSERT_GT(dof, 3 * 50 * 99);
    const double gyro_sigma = imu.gyro_noise_density * std::sqrt(rate);
    const double accel_sigma = imu.accel_noise_density * std::sqrt(rate);
    EXPECT_NEAR(std::sqrt(gyro_ss / dof), gyro_sigma, 0.03 * gyro_sigma);
    EXPECT_NEAR(std::sqrt(accel_ss / dof), accel_sigma, 0.03 * accel_sigma);
    // The samples' mean is the true reading plus the turn-on bias (the walk adds little).
    Eigen::Vector3d gyro_mean = Eigen::Vector3d::Zero();
    for (int i = 0; i < 2 * per_window; ++i) gyro_mean += still.samples[i].gyro;
    gyro_mean /= 2 * per_window;
    EXPECT_LT((gyro_mean - imu.gyro_bias).norm(), 5 * gyro_sigma / std::sqrt(2 * per_window));

    // Bias walk: increments over windows of 1 s and 16 s, over ten seeds' whole logs.
    for (const double window : {1.0, 16.0}) {
      const std::size_t step = static_cast<std::size_t>(std::llround(window * rate));
      double gyro_var = 0.0, accel_var = 0.0;
      int count = 0;
      for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        const ImuSimulation run =
            simulateImu(world.trajectory, spec.sensors, world.trajectory.duration(), false, seed);
        for (std::size_t i = 0; i + step < run.samples.size(); i += step) {
          gyro_var += (run.gyro_bias[i + step] - run.gyro_bias[i]).squaredNorm();
          accel_var += (run.accel_bias[i + step] - run.accel_bias[i]).squaredNorm();
          count += 3;
        }
      }
      const double tolerance = 4.0 / std::sqrt(2.0 * count);  // 4 sigma of a std estimate
      EXPECT_NEAR(std::sqrt(gyro_var / count), imu.gyro_random_walk * std::sqrt(window),
                  tolerance * imu.gyro_random_walk * std::sqrt(window))
          << window << " s, " << count << " increments";
      EXPECT_NEAR(std::sqrt(accel_var / count), imu.accel_random_walk * std::sqrt(window),
                  tolerance * imu.accel_random_walk * std::sqrt(window))
          << window << " s";
    }
  }
}

}  // namespace
}  // namespace storey::sim
