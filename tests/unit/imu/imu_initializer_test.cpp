#include "imu/imu_initializer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "common/error.h"
#include "synthetic_imu.h"

namespace storey {
namespace {

using test::SyntheticTrajectory;

constexpr double kDeg = M_PI / 180.0;

Eigen::Quaterniond fromEuler(double yaw, double pitch, double roll) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
}

/// Angle between the estimated and the true world z seen from the IMU [rad].
double gravityDirectionError(const Eigen::Quaterniond& q_est, const Eigen::Quaterniond& q_true) {
  const Eigen::Vector3d up_est = q_est.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_true = q_true.conjugate() * Eigen::Vector3d::UnitZ();
  return std::acos(std::min(1.0, up_est.dot(up_true)));
}

struct Mounting {
  const char* name;
  Eigen::Quaterniond q_world_imu;
};

std::vector<Mounting> mountings() {
  std::vector<Mounting> m = {
      {"level", fromEuler(0.3, 0, 0)},
      {"upside down", fromEuler(-1.0, 0, M_PI)},
      {"x up (pitch -90)", fromEuler(0.5, -M_PI / 2, 0)},
      {"x down (pitch +90)", fromEuler(2.0, M_PI / 2, 0.3)},
      {"y up (roll +90)", fromEuler(0, 0, M_PI / 2)},
      {"y down, tilted", fromEuler(1, 0.2, -M_PI / 2)},
      {"upside down, pitched", fromEuler(3.0, 0.4, 2.9)},
  };
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0, 1);
  for (int i = 0; i < 5; ++i) {
    m.push_back({"random", Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized()});
  }
  return m;
}

// Tactical IMU (default noise), biases of typical size; accel bias along
// gravity recovered, gyro bias within noise, gravity direction within 0.1 deg.
TEST(ImuInitializer, RecoversGravityAndBiasesInAnyMounting) {
  const ImuNoise noise;
  int tested = 0;
  for (const Mounting& m : mountings()) {
    const SyntheticTrajectory still = SyntheticTrajectory::still(m.q_world_imu);
    const Eigen::Vector3d up_imu = m.q_world_imu.conjugate() * Eigen::Vector3d::UnitZ();
    test::ImuSimOptions o;
    o.duration = 1.5;
    o.white_noise = true;
    o.seed = 5 + static_cast<std::uint32_t>(tested);
    o.bias.gyro = Eigen::Vector3d(0.01, -0.02, 0.015);  // 1 deg/s
    // 0.05 m/s^2 along gravity plus 0.01 m/s^2 orthogonal to it.
    const Eigen::Vector3d ortho = up_imu.unitOrthogonal();
    o.bias.accel = 0.05 * up_imu + 0.01 * ortho;
    const auto samples = test::simulateImu(still, o);
    const ImuInitResult r = initializeImuFromStill(samples, noise);

    const Eigen::Quaterniond q_est = r.state.T_world_imu.rotation();
    const double dir_err = gravityDirectionError(q_est, m.q_world_imu);
    EXPECT_LT(dir_err, 0.1 * kDeg) << m.name;
    // The orthogonal bias tilts the estimate by about |b_perp| / g (documented).
    EXPECT_NEAR(dir_err, 0.01 / 9.81, 2e-4) << m.name;
    // Gyro bias within 4 sigma of the mean of 1 s of white noise (sigma = density / sqrt(1 s)).
    EXPECT_LT((r.state.bias.gyro - o.bias.gyro).cwiseAbs().maxCoeff(),
              4.0 * noise.gyro_noise_density)
        << m.name;
    // Accel bias: its component along gravity is recovered, the orthogonal one is not.
    EXPECT_NEAR(r.state.bias.accel.dot(up_imu), 0.05, 3e-3) << m.name;  // 5 sigma of the mean
    EXPECT_LT((r.state.bias.accel - r.state.bias.accel.dot(up_imu) * up_imu).norm(), 1e-3)
        << m.name;
    // The initial state reproduces the mean specific force: R^T (0,0,g) + b_a = mean accel.
    const Eigen::Vector3d predicted =
        q_est.conjugate() * Eigen::Vector3d(0, 0, noise.gravity) + r.state.bias.accel;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < r.stats.samples; ++k) mean += samples[k].accel;
    EXPECT_LT((predicted - mean / static_cast<double>(r.stats.samples)).norm(), 1e-9) << m.name;
    // Yaw = 0 (ZYX): the roll-pitch rotation has no heading term, i.e. world
    // y of the IMU's x axis is 0 unless x is vertical.
    const Eigen::Vector3d x_world = q_est * Eigen::Vector3d::UnitX();
    if (std::abs(x_world.z()) < 0.99) {
      EXPECT_NEAR(x_world.y(), 0.0, 1e-12) << m.name;
      EXPECT_GT(x_world.x(), 0.0) << m.name;
    }
    EXPECT_EQ(r.state.T_world_imu.translation(), Eigen::Vector3d::Zero());
    EXPECT_EQ(r.state.v_world_imu, Eigen::Vector3d::Zero());
    EXPECT_EQ(r.stats.samples, 401u);  // 1 s at 400 Hz, both ends included
    EXPECT_EQ(r.state.stamp_ns, test::kBaseNs + 1'000'000'000);
    ++tested;
  }
  EXPECT_EQ(tested, 12);
}

TEST(ImuInitializer, AccelBiasAlongGravityCanBeTurnedOff) {
  const SyntheticTrajectory still = SyntheticTrajectory::still(Eigen::Quaterniond::Identity());
  test::ImuSimOptions o;
  o.bias.accel = Eigen::Vector3d(0, 0, 0.1);
  const auto samples = test::simulateImu(still, o);
  ImuInitConfig config;
  EXPECT_NEAR(initializeImuFromStill(samples, ImuNoise(), config).state.bias.accel.z(), 0.1, 1e-9);
  config.accel_bias_along_gravity = false;
  EXPECT_EQ(initializeImuFromStill(samples, ImuNoise(), config).state.bias.accel,
            Eigen::Vector3d::Zero());
}

std::string errorOf(const std::vector<ImuSample>& samples,
                    const ImuInitConfig& config = ImuInitConfig()) {
  try {
    initializeImuFromStill(samples, ImuNoise(), config);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ImuInitializer, WalkingStartIsAnErrorThatSaysWhatToDo) {
  const auto samples = test::simulateImu(SyntheticTrajectory::trot(), test::ImuSimOptions());
  const std::string msg = errorOf(samples);
  std::cout << "[ message  ] " << msg << "\n";
  EXPECT_NE(msg.find("the first 1 s of IMU data are not still: gyro std"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("rad/s >"), std::string::npos) << msg;
  EXPECT_NE(msg.find("record the first 1 s with the sensor at rest"),
            std::string::npos)
      << msg;
}

TEST(ImuInitializer, OtherBadStartsAreErrors) {
  // Translation only (shaking along x at 2 Hz, 1 cm): accel spread, no rotation.
  test::SyntheticTrajectory shake = SyntheticTrajectory::still(Eigen::Quaterniond::Identity());
  shake.x.terms = {{0.01, 2 * M_PI * 2.0, 0.0}};
  EXPECT_NE(errorOf(test::simulateImu(shake, test::ImuSimOptions())).find("accel std"),
            std::string::npos);
  // Steady rotation at 0.3 rad/s: no spread, but not still.
  test::SyntheticTrajectory spin = SyntheticTrajectory::still(Eigen::Quaterniond::Identity());
  spin.yaw.rate = 0.3;
  EXPECT_NE(errorOf(test::simulateImu(spin, test::ImuSimOptions())).find("mean gyro"),
            std::string::npos);
  // Accelerations in g instead of m/s^2.
  auto in_g = test::simulateImu(SyntheticTrajectory::still(Eigen::Quaterniond::Identity()),
                                test::ImuSimOptions());
  for (ImuSample& s : in_g) s.accel /= 9.81;
  EXPECT_NE(errorOf(in_g).find("in g?"), std::string::npos) << errorOf(in_g);
  // Too short.
  test::ImuSimOptions short_log;
  short_log.duration = 0.5;
  const std::string msg = errorOf(
      test::simulateImu(SyntheticTrajectory::still(Eigen::Quaterniond::Identity()), short_log));
  EXPECT_NE(msg.find("last only 0.5 s"), std::string::npos) << msg;
  EXPECT_NE(errorOf({}).find("0 IMU samples"), std::string::npos);
}

// A noisy consumer MEMS IMU at 1 kHz at rest is not taken as moving
// (noise-aware threshold), and hand tremor-level motion passes.
TEST(ImuInitializer, NoisyMemsAtRestPasses) {
  ImuNoise mems;
  mems.rate_hz = 1000;
  mems.gyro_noise_density = 5e-4;   // 0.03 deg/s/sqrt(Hz): worse than most consumer parts
  mems.accel_noise_density = 3e-3;  // 300 ug/sqrt(Hz)
  test::ImuSimOptions o;
  o.rate_hz = 1000;
  o.duration = 1.2;
  o.white_noise = true;
  o.noise = mems;
  o.bias.gyro = Eigen::Vector3d(0.05, 0.02, -0.03);
  const auto samples = test::simulateImu(SyntheticTrajectory::still(fromEuler(0, 0, M_PI)), o);
  const ImuInitResult r = initializeImuFromStill(samples, mems);
  std::cout << "[ measured ] MEMS at rest: gyro std " << r.stats.gyro_std << " (limit "
            << r.stats.gyro_std_limit << ") rad/s, accel std " << r.stats.accel_std << " (limit "
            << r.stats.accel_std_limit << ") m/s^2\n";
  EXPECT_GT(r.stats.gyro_std,
            ImuInitConfig().max_gyro_std);  // fixture check: noisier than the base threshold
  EXPECT_LT(gravityDirectionError(r.state.T_world_imu.rotation(), fromEuler(0, 0, M_PI)),
            0.1 * kDeg);
}

TEST(ImuInitializer, ConfigValidationNamesTheKey) {
  ImuInitConfig config;
  EXPECT_NO_THROW(config.validate());
  config.noise_margin = 0.5;
  try {
    config.validate();
    FAIL() << "expected storey::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("noise_margin"), std::string::npos) << e.what();
  }
  ImuPreintegrationConfig pre;
  EXPECT_NO_THROW(pre.validate());
  pre.repropagate_gyro_bias_change = 0.0;
  EXPECT_THROW(pre.validate(), Error);
}

TEST(ImuInitializer, GravityAlignedRotationMapsUpToZ) {
  std::mt19937 rng(2);
  std::normal_distribution<double> n(0, 1);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d up = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
    EXPECT_LT((gravityAlignedRotation(up) * up - Eigen::Vector3d::UnitZ()).norm(), 1e-14);
  }
  for (const Eigen::Vector3d& up : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0),
                                    Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0)}) {
    EXPECT_LT((gravityAlignedRotation(up) * up - Eigen::Vector3d::UnitZ()).norm(), 1e-14)
        << up.transpose();
  }
}

}  // namespace
}  // namespace storey
