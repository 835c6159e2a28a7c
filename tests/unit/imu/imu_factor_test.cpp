#include "imu/imu_factor.h"

#include <ceres/gradient_checker.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <iostream>
#include <memory>
#include <random>

#include "imu/imu_state_blocks.h"
#include "imu/so3.h"
#include "synthetic_imu.h"

namespace storey {
namespace {

using test::angleBetween;
using test::kBaseNs;
using test::SyntheticTrajectory;

std::int64_t ns(double seconds) {
  return kBaseNs + secondsToNs(seconds);
}

struct Fixture {
  SyntheticTrajectory tr = SyntheticTrajectory::trot(
      Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Eigen::Vector3d(1, -1, 2).normalized())));
  ImuBias bias;
  std::vector<ImuSample> samples;
  std::int64_t t_i = ns(0.31234), t_j = ns(0.41234);
  explicit Fixture(double rate = 400.0) {
    bias.gyro = Eigen::Vector3d(0.004, -0.003, 0.002);
    bias.accel = Eigen::Vector3d(0.05, 0.03, -0.04);
    test::ImuSimOptions o;
    o.rate_hz = rate;
    o.bias = bias;
    samples = test::simulateImu(tr, o);
  }
  ImuPreintegration preintegrate(const ImuBias& bias_lin) const {
    return ImuPreintegration::fromSamples(samples, t_i, t_j, bias_lin, ImuNoise());
  }
};

ImuState perturbed(const ImuState& s, std::mt19937& rng, double scale) {
  std::normal_distribution<double> n(0.0, scale);
  const auto v3 = [&] { return Eigen::Vector3d(n(rng), n(rng), n(rng)); };
  ImuState out = s;
  out.T_world_imu =
      Pose(so3::expQuaternion(v3()) * s.T_world_imu.rotation(), s.T_world_imu.translation() + v3());
  out.v_world_imu += v3();
  out.bias.gyro += 0.01 * v3();
  out.bias.accel += 0.1 * v3();
  return out;
}

TEST(ImuFactor, ResidualIsZeroForTheTrueStates) {
  for (double rate : {400.0, 1000.0}) {
    const Fixture f(rate);
    const ImuState si = f.tr.state(f.t_i, f.bias), sj = f.tr.state(f.t_j, f.bias);
    // Fixture check: the states differ in every component.
    ASSERT_GT((sj.T_world_imu.translation() - si.T_world_imu.translation()).norm(), 0.05);
    ASSERT_GT(angleBetween(sj.T_world_imu.rotation(), si.T_world_imu.rotation()), 0.02);
    ASSERT_GT((sj.v_world_imu - si.v_world_imu).norm(), 0.05);
    // Linearised at the true biases, and 0.005 rad/s / 0.05 m/s^2 away (first-order correction).
    ImuBias off = f.bias;
    off.gyro += Eigen::Vector3d(0.005, 0, -0.003);
    off.accel += Eigen::Vector3d(0, 0.05, 0.02);
    for (const ImuBias& bias_lin : {f.bias, off}) {
      const ImuFactor factor(f.preintegrate(bias_lin));
      const Eigen::Matrix<double, 15, 1> r = factor.residual(si, sj);
      const Eigen::Matrix<double, 15, 1> rw = factor.sqrtInformation() * r;
      std::cout << "[ measured ] " << rate << " Hz, true states: |r_R| " << r.head<3>().norm()
                << " rad, |r_v| " << r.segment<3>(3).norm() << " m/s, |r_p| "
                << r.segment<3>(6).norm() << " m, whitened |r| " << rw.norm() << "\n";
      // Only the discretisation error remains (bound: synthetic_imu.h).
      const test::IntegrationErrorBound b = test::integrationErrorBound(
          f.tr, rate, test::secondsSinceBase(f.t_i), test::secondsSinceBase(f.t_j));
      EXPECT_LT(r.head<3>().norm(), b.rotation);
      EXPECT_LT(r.segment<3>(3).norm(), b.velocity);
      EXPECT_LT(r.segment<3>(6).norm(), b.position);
      EXPECT_LT(r.tail<6>().norm(), 1e-15);
      EXPECT_LT(rw.norm(), rate < 500 ? 1.5 : 0.3);  // within the white noise (15 dof)
    }
  }
}

// Exactly zero (rounding) for the state the preintegration itself predicts,
// with biases away from the linearisation point: the factor and predict()
// apply the same first-order bias correction.
TEST(ImuFactor, ResidualIsZeroForThePredictedState) {
  const Fixture f;
  const ImuPreintegration pre = f.preintegrate(ImuBias());
  const ImuFactor factor(pre);
  ImuState si = f.tr.state(f.t_i, f.bias);
  const ImuState sj = pre.predict(si);
  const Eigen::Matrix<double, 15, 1> r = factor.residual(si, sj);
  EXPECT_LT(r.head<3>().norm(), 1e-13);
  EXPECT_LT(r.segment<3>(3).norm(), 1e-13);
  EXPECT_LT(r.segment<3>(6).norm(), 1e-13);
  EXPECT_LT(r.tail<6>().norm(), 1e-15);
  EXPECT_GT((sj.T_world_imu.translation() - si.T_world_imu.translation()).norm(), 0.05);
}

TEST(ImuFactor, ResidualGrowsWithStateErrors) {
  const Fixture f;
  const ImuFactor factor(f.preintegrate(f.bias));
  const ImuState si = f.tr.state(f.t_i, f.bias);
  ImuState sj = f.tr.state(f.t_j, f.bias);
  sj.T_world_imu =
      Pose(sj.T_world_imu.rotation(), sj.T_world_imu.translation() + Eigen::Vector3d(0, 0, 0.01));
  const Eigen::Matrix<double, 15, 1> r0 = factor.residual(si, f.tr.state(f.t_j, f.bias));
  const Eigen::Matrix<double, 15, 1> r = factor.residual(si, sj);
  // 1 cm up at t_j adds R_i^T (0, 0, 0.01) to r_p, nothing else.
  EXPECT_LT((r.segment<3>(6) - r0.segment<3>(6) -
             si.T_world_imu.rotation().conjugate() * Eigen::Vector3d(0, 0, 0.01))
                .norm(),
            1e-12);
  EXPECT_LT((r.head<6>() - r0.head<6>()).norm(), 1e-12);
}

// Analytic Jacobians against Ceres' numeric ones, in the tangent spaces of
// the manifolds, at states near and far from the truth and with biases away
// from the linearisation point.
TEST(ImuFactor, JacobiansMatchNumericDifferentiationOnTheManifolds) {
  const Fixture f;
  const ImuBias bias_lin = f.bias;
  const ImuFactor factor(f.preintegrate(bias_lin));
  const ImuPoseManifold pose_manifold;
  const std::vector<const ceres::Manifold*> manifolds = {&pose_manifold, nullptr, &pose_manifold,
                                                         nullptr};
  const ceres::GradientChecker checker(&factor, &manifolds, ceres::NumericDiffOptions());
  std::mt19937 rng(21);
  int probes = 0;
  for (double scale : {1e-3, 0.05, 0.4}) {
    for (int i = 0; i < 5; ++i) {
      const ImuStateBlocks bi =
          ImuStateBlocks::fromState(perturbed(f.tr.state(f.t_i, f.bias), rng, scale));
      const ImuStateBlocks bj =
          ImuStateBlocks::fromState(perturbed(f.tr.state(f.t_j, f.bias), rng, scale));
      const double* params[4] = {bi.pose, bi.motion, bj.pose, bj.motion};
      ceres::GradientChecker::ProbeResults results;
      EXPECT_TRUE(checker.Probe(params, 1e-6, &results)) << results.error_log;
      // Fixture check: the residual is not trivially small and the rotation part is exercised.
      EXPECT_GT(results.residuals.norm(), 1.0);
      EXPECT_GT((results.local_jacobians[0].block<3, 3>(0, 3).norm()), 1.0);
      ++probes;
    }
  }
  EXPECT_EQ(probes, 15);
}

// The factor with gravity's tilt as a parameter: its Jacobians (the tilt's
// included) against numeric ones, and at zero tilt it is the plain factor.
TEST(ImuGravityFactor, JacobiansMatchNumericAndZeroTiltIsThePlainFactor) {
  const Fixture f;
  const ImuPreintegration preintegration = f.preintegrate(f.bias);
  const ImuFactor plain(preintegration);
  const ImuGravityFactor factor(preintegration);
  const ImuPoseManifold pose_manifold;
  const std::vector<const ceres::Manifold*> manifolds = {&pose_manifold, nullptr, &pose_manifold,
                                                         nullptr, nullptr};
  const ceres::GradientChecker checker(&factor, &manifolds, ceres::NumericDiffOptions());
  std::mt19937 rng(5);
  for (double tilt_size : {0.0, 0.004, 0.05}) {
    const ImuStateBlocks bi = ImuStateBlocks::fromState(perturbed(f.tr.state(f.t_i, f.bias), rng, 1e-3));
    const ImuStateBlocks bj = ImuStateBlocks::fromState(perturbed(f.tr.state(f.t_j, f.bias), rng, 1e-3));
    double tilt[2] = {tilt_size, -0.5 * tilt_size};
    const double* params[5] = {bi.pose, bi.motion, bj.pose, bj.motion, tilt};
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(params, 1e-6, &results)) << results.error_log;
    if (tilt_size == 0.0) {
      Eigen::Matrix<double, 15, 1> r_plain, r_tilt;
      ASSERT_TRUE(plain.Evaluate(params, r_plain.data(), nullptr));
      ASSERT_TRUE(factor.Evaluate(params, r_tilt.data(), nullptr));
      EXPECT_LT((r_plain - r_tilt).norm(), 1e-12);
    } else {
      EXPECT_GT(results.local_jacobians[4].norm(), 1.0);  // the tilt is exercised
    }
  }
  // tiltedGravity keeps |g|; a tilt about x turns it towards +y.
  const double t[2] = {0.01, 0.0};
  const Eigen::Vector3d g = tiltedGravity(t, 9.81);
  EXPECT_NEAR(g.norm(), 9.81, 1e-12);
  EXPECT_NEAR(g.y(), 9.81 * std::sin(0.01), 1e-9);  // Exp(a e_x) (0, 0, -g) = (0, g sin a, -g cos a)
}

TEST(ImuFactor, EvaluateWithAndWithoutJacobiansAgree) {
  const Fixture f;
  const ImuFactor factor(f.preintegrate(ImuBias()));
  std::mt19937 rng(3);
  const ImuStateBlocks bi = ImuStateBlocks::fromState(perturbed(f.tr.state(f.t_i), rng, 0.1));
  const ImuStateBlocks bj = ImuStateBlocks::fromState(perturbed(f.tr.state(f.t_j), rng, 0.1));
  const double* params[4] = {bi.pose, bi.motion, bj.pose, bj.motion};
  double r1[15], r2[15], j0[15 * 7], j1[15 * 9], j3[15 * 9];
  double* jac[4] = {j0, j1, nullptr, j3};  // a constant block has no Jacobian
  ASSERT_TRUE(factor.Evaluate(params, r1, nullptr));
  ASSERT_TRUE(factor.Evaluate(params, r2, jac));
  for (int k = 0; k < 15; ++k) EXPECT_EQ(r1[k], r2[k]);
}

// The Ceres helper and the manifold in a real solve: with state i fixed, the
// IMU factor alone determines state j (15 equations, 15 unknowns).
TEST(ImuFactor, SolvingRecoversTheNextState) {
  const Fixture f;
  auto* factor = new ImuFactor(f.preintegrate(ImuBias()));  // owned by the problem
  const ImuState truth_i = f.tr.state(f.t_i, f.bias), truth_j = f.tr.state(f.t_j, f.bias);
  ImuStateBlocks bi = ImuStateBlocks::fromState(truth_i);
  std::mt19937 rng(9);
  ImuStateBlocks bj = ImuStateBlocks::fromState(perturbed(truth_j, rng, 0.2));
  ceres::Problem problem;
  addImuStateBlocks(problem, bi);
  addImuStateBlocks(problem, bj);
  addImuStateBlocks(problem, bj);  // adding twice is harmless
  problem.SetParameterBlockConstant(bi.pose);
  problem.SetParameterBlockConstant(bi.motion);
  problem.AddResidualBlock(factor, nullptr, bi.pose, bi.motion, bj.pose, bj.motion);
  ASSERT_EQ(problem.NumParameterBlocks(), 4);
  EXPECT_EQ(problem.ParameterBlockTangentSize(bj.pose), 6);
  ceres::Solver::Options options;
  options.max_num_iterations = 20;
  options.linear_solver_type = ceres::DENSE_QR;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable()) << summary.FullReport();
  const ImuState sj = bj.toState(f.t_j);
  EXPECT_NEAR(Eigen::Map<const Eigen::Quaterniond>(bj.pose + 3).norm(), 1.0, 1e-12);
  const test::IntegrationErrorBound b = test::integrationErrorBound(
      f.tr, 400.0, test::secondsSinceBase(f.t_i), test::secondsSinceBase(f.t_j));
  EXPECT_LT(angleBetween(sj.T_world_imu.rotation(), truth_j.T_world_imu.rotation()), b.rotation);
  EXPECT_LT((sj.T_world_imu.translation() - truth_j.T_world_imu.translation()).norm(), b.position);
  EXPECT_LT((sj.v_world_imu - truth_j.v_world_imu).norm(), b.velocity);
  // And exactly the preintegration's own prediction.
  const ImuState pred = f.preintegrate(ImuBias()).predict(truth_i);
  EXPECT_LT((sj.T_world_imu.translation() - pred.T_world_imu.translation()).norm(), 1e-9);
  EXPECT_LT((sj.bias.gyro - truth_j.bias.gyro).norm(), 1e-9);
  EXPECT_LT(summary.final_cost, 1e-2);
  EXPECT_LT(summary.iterations.size(), 10u);
}

}  // namespace
}  // namespace storey
