#include "sim/imu_simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "sim/world.h"

namespace storey::sim {
namespace {

struct State {
  Eigen::Quaterniond q;  // R_world_imu
  Eigen::Vector3d v, p;  // world
};

State derivative(const State& s, const Eigen::Vector3d& gyro, const Eigen::Vector3d& accel,
                 double g) {
  State d;
  const Eigen::Quaterniond omega(0.0, gyro.x(), gyro.y(), gyro.z());
  d.q.coeffs() = 0.5 * (s.q * omega).coeffs();
  d.v = s.q * accel + Eigen::Vector3d(0, 0, -g);
  d.p = s.v;
  return d;
}

State add(const State& s, const State& d, double h) {
  State r;
  r.q.coeffs() = s.q.coeffs() + h * d.q.coeffs();
  r.v = s.v + h * d.v;
  r.p = s.p + h * d.p;
  return r;
}

/// RK4 over the samples, the input between samples by cubic interpolation.
State integrate(const std::vector<ImuSample>& samples, std::size_t last, const State& start,
                double g) {
  State s = start;
  auto at = [&](std::ptrdiff_t i) {
    return samples[std::clamp<std::ptrdiff_t>(i, 0, samples.size() - 1)];
  };
  for (std::size_t k = 0; k < last; ++k) {
    const double h = (samples[k + 1].stamp_ns - samples[k].stamp_ns) * 1e-9;
    const ImuSample a = at(k - 1), b = at(k), c = at(k + 1), d = at(k + 2);
    const Eigen::Vector3d gyro_mid = (-a.gyro + 9 * b.gyro + 9 * c.gyro - d.gyro) / 16;
    const Eigen::Vector3d accel_mid = (-a.accel + 9 * b.accel + 9 * c.accel - d.accel) / 16;
    const State k1 = derivative(s, b.gyro, b.accel, g);
    const State k2 = derivative(add(s, k1, h / 2), gyro_mid, accel_mid, g);
    const State k3 = derivative(add(s, k2, h / 2), gyro_mid, accel_mid, g);
    const State k4 = derivative(add(s, k3, h), c.gyro, c.accel, g);
    s.q.coeffs() += h / 6 * (k1.q.coeffs() + 2 * k2.q.coeffs() + 2 * k3.q.coeffs() + k4.q.coeffs());
    s.q.normalize();
    s.v += h / 6 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v);
    s.p += h / 6 * (k1.p + 2 * k2.p + 2 * k3.p + k4.p);
  }
  return s;
}

void expectIntegrationMatchesTruth(const BuildingSpec& spec) {
  const World world = makeWorld(spec);
  const double seconds = 60.0;
  const ImuSimulation imu =
      simulateImu(world.trajectory, spec.sensors, seconds + 0.1, true, spec.seed);
  const FrameKinematics k0 = world.trajectory.frame(0.0, spec.sensors.T_body_imu);
  const State start{k0.T_world_frame.rotation(), k0.v_world, k0.T_world_frame.translation()};
  const std::size_t last = static_cast<std::size_t>(std::llround(seconds * spec.sensors.imu.rate));
  ASSERT_LT(last, imu.samples.size());
  ASSERT_EQ(imu.samples[last].stamp_ns, 60'000'000'000LL);
  const State end = integrate(imu.samples, last, start, spec.sensors.imu.gravity);
  const FrameKinematics truth = world.trajectory.frame(seconds, spec.sensors.T_body_imu);
  // The fixture really moves: tens of metres, and climbs.
  double farthest = 0.0;
  for (double t = 0.0; t <= seconds; t += 1.0) {
    const Eigen::Vector3d p =
        world.trajectory.frame(t, spec.sensors.T_body_imu).T_world_frame.translation();
    farthest = std::max(farthest, (p - start.p).norm());
  }
  EXPECT_GT(farthest, 10.0);
  const double error = (end.p - truth.T_world_frame.translation()).norm();
  ::testing::Test::RecordProperty("position_error_after_60s_m", std::to_string(error));
  std::printf("IMU at %.0f Hz: %.1f m travelled, position error after 60 s %.2e m\n",
              spec.sensors.imu.rate, (truth.T_world_frame.translation() - start.p).norm(), error);
  EXPECT_LT(error, 0.01);
  EXPECT_LT((end.v - truth.v_world).norm(), 0.002);
  EXPECT_LT(Eigen::AngleAxisd(end.q.conjugate() * truth.T_world_frame.rotation()).angle(), 1e-4);
}

TEST(SimImu, NoiseFreeIntegrationStaysWithin1cmAfter60s) {
  expectIntegrationMatchesTruth(loadBuildingSpec("default"));
}

TEST(SimImu, NoiseFreeIntegrationWithRotatedImuAt200Hz) {
  BuildingSpec spec = loadBuildingSpec("default");
  spec.sensors.imu.rate = 200.0;
  spec.sensors.T_body_imu =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()) *
                              Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY())),
           Eigen::Vector3d(-0.1, 0.05, -0.03));
  expectIntegrationMatchesTruth(spec);
}

/// A person's walk (faster turns, a bouncier gait) with the IMU 0.3 m from the
/// device's centre in an odd orientation: the readings still integrate to the truth.
TEST(SimImu, NoiseFreeIntegrationHandheldWithLeverArm) {
  BuildingSpec spec = loadBuildingSpec("default");
  spec.robot = robotForMotion(RobotMotion::kHandheld);
  spec.sensors.imu = imuGrade(ImuGrade::kConsumer, 200.0);
  spec.sensors.T_body_imu =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(2.2, Eigen::Vector3d(0.2, 1.0, -0.4).normalized())),
           Eigen::Vector3d(0.3, 0.0, 0.0));
  expectIntegrationMatchesTruth(spec);
}

TEST(SimImu, StillPeriodsReadGravity) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.sensors.T_body_imu =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized())),
           Eigen::Vector3d(0.1, 0.0, 0.0));
  const World world = makeWorld(spec);
  const double g = spec.sensors.imu.gravity;
  const ImuSimulation perfect =
      simulateImu(world.trajectory, spec.sensors, world.trajectory.duration(), true, 1);
  int still = 0;
  for (std::size_t i = 0; i < perfect.samples.size(); ++i) {
    const double t = perfect.samples[i].stamp_ns * 1e-9;
    if (t > world.trajectory.stillTime() &&
        t < world.trajectory.duration() - world.trajectory.stillTime())
      continue;
    const Eigen::Vector3d expected =
        perfect.T_world_imu[i].rotation().conjugate() * Eigen::Vector3d(0, 0, g);
    EXPECT_LT((perfect.samples[i].accel - expected).norm(), 1e-9);
    EXPECT_LT(perfect.samples[i].gyro.norm(), 1e-9);
    ++still;
  }
  EXPECT_GE(still, 2 * 2 * 400);

  // With noise: the mean is gravity + the initial bias, the spread is density * sqrt(rate).
  const ImuSimulation noisy = simulateImu(world.trajectory, spec.sensors, 2.0, false, 5);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(), gyro_mean = Eigen::Vector3d::Zero();
  for (const ImuSample& s : noisy.samples) {
    mean += s.accel;
    gyro_mean += s.gyro;
  }
  const double n = static_cast<double>(noisy.samples.size());
  mean /= n;
  gyro_mean /= n;
  Eigen::Vector3d var = Eigen::Vector3d::Zero(), gyro_var = Eigen::Vector3d::Zero();
  for (const ImuSample& s : noisy.samples) {
    var += (s.accel - mean).cwiseAbs2();
    gyro_var += (s.gyro - gyro_mean).cwiseAbs2();
  }
  var /= n - 1;
  gyro_var /= n - 1;
  const Eigen::Vector3d expected =
      noisy.T_world_imu.front().rotation().conjugate() * Eigen::Vector3d(0, 0, g) +
      spec.sensors.imu.accel_bias;
  EXPECT_LT((mean - expected).norm(), 0.005);
  EXPECT_LT((gyro_mean - spec.sensors.imu.gyro_bias).norm(), 5e-4);
  const double accel_sigma =
      spec.sensors.imu.accel_noise_density * std::sqrt(spec.sensors.imu.rate);
  const double gyro_sigma = spec.sensors.imu.gyro_noise_density * std::sqrt(spec.sensors.imu.rate);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(std::sqrt(var[a]), accel_sigma, 0.12 * accel_sigma);
    EXPECT_NEAR(std::sqrt(gyro_var[a]), gyro_sigma, 0.12 * gyro_sigma);
  }
}

}  // namespace
}  // namespace storey::sim
