#include "imu/imu_preintegration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "common/error.h"
#include "imu/imu_pose_table.h"
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

struct PredictionError {
  double rotation, velocity, position;  // [rad], [m/s], [m]
};

PredictionError predictionError(const SyntheticTrajectory& tr,
                                const std::vector<ImuSample>& samples, std::int64_t t_i,
                                std::int64_t t_j, const ImuBias& bias, const ImuNoise& noise) {
  const ImuPreintegration pre = ImuPreintegration::fromSamples(samples, t_i, t_j, bias, noise);
  const ImuState truth_j = tr.state(t_j, bias);
  const ImuState pred_j = pre.predict(tr.state(t_i, bias));
  return {angleBetween(pred_j.T_world_imu.rotation(), truth_j.T_world_imu.rotation()),
          (pred_j.v_world_imu - truth_j.v_world_imu).norm(),
          (pred_j.T_world_imu.translation() - truth_j.T_world_imu.translation()).norm()};
}

// The fixture really moves like a trotting robot: otherwise the accuracy
// tests below would test less than they claim.
TEST(ImuPreintegration, FixtureMovesAndRotatesLikeATrot) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  double max_gyro = 0.0, max_accel = 0.0;
  for (double t = 0.0; t < 1.0; t += 1e-3) {
    max_gyro = std::max(max_gyro, tr.angularRate(t).norm());
    max_accel = std::max(max_accel, tr.acceleration(t).norm());
  }
  EXPECT_GT((tr.position(1.0) - tr.position(0.0)).norm(), 0.5);
  EXPECT_GT(angleBetween(tr.rotation(1.0), tr.rotation(0.0)), 0.3);
  EXPECT_GT(max_gyro, 0.8);
  EXPECT_GT(max_accel, 3.0);
  // Analytic derivatives are consistent with the values (central differences).
  const double h = 1e-5;
  for (double t : {0.1, 0.37, 0.8}) {
    EXPECT_LT(((tr.position(t + h) - tr.position(t - h)) / (2 * h) - tr.velocity(t)).norm(), 1e-8);
    EXPECT_LT(((tr.velocity(t + h) - tr.velocity(t - h)) / (2 * h) - tr.acceleration(t)).norm(),
              1e-6);
    const Eigen::Vector3d w_numeric =
        so3::logQuaternion(tr.rotation(t - h).conjugate() * tr.rotation(t + h)) / (2 * h);
    EXPECT_LT((w_numeric - tr.angularRate(t)).norm(), 1e-7);
  }
}

// Noise-free data: the prediction from the true state at t_i matches the
// truth at t_j within the discretisation bound derived in synthetic_imu.h
// (dt^2/6 max|jerk| for the velocity: 1.4e-4 m/s at 400 Hz for this trot,
// whose 5 Hz bounce has a jerk of 130 m/s^3), and within the brief's
// targets at 400 Hz: < 1 mm over 0.1 s, < 1 cm over 1 s.
TEST(ImuPreintegration, NoiseFreeMatchesTruthAtThreeRates) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())));
  ImuNoise noise;
  ImuBias bias;
  bias.gyro = Eigen::Vector3d(0.01, -0.02, 0.005);
  bias.accel = Eigen::Vector3d(0.05, 0.1, -0.08);
  const double t_i = 0.2123457;  // scan times off the sample grid
  for (double rate : {100.0, 400.0, 1000.0}) {
    test::ImuSimOptions o;
    o.rate_hz = rate;
    o.duration = 1.5;
    o.bias = bias;
    const auto samples = test::simulateImu(tr, o);
    for (double duration : {0.1, 1.0}) {
      const PredictionError e =
          predictionError(tr, samples, ns(t_i), ns(t_i + duration), bias, noise);
      const test::IntegrationErrorBound b =
          test::integrationErrorBound(tr, rate, t_i, t_i + duration);
      std::cout << "[ measured ] " << rate << " Hz over " << duration << " s: rotation "
                << e.rotation << " rad (bound " << b.rotation << "), velocity " << e.velocity
                << " m/s (bound " << b.velocity << "), position " << e.position << " m (bound "
                << b.position << ")\n";
      EXPECT_LT(e.rotation, b.rotation) << rate << " Hz " << duration << " s";
      EXPECT_LT(e.velocity, b.velocity) << rate << " Hz " << duration << " s";
      EXPECT_LT(e.position, b.position) << rate << " Hz " << duration << " s";
      if (rate == 400.0) {
        EXPECT_LT(e.position, duration < 0.5 ? 1e-3 : 1e-2);
      }
    }
  }
}

// The scheme is second order: 4x the rate gives about 16x less error.
TEST(ImuPreintegration, ErrorIsSecondOrderInTheSamplePeriod) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  ImuNoise noise;
  double err[2];
  const double rates[2] = {100.0, 400.0};
  for (int i = 0; i < 2; ++i) {
    test::ImuSimOptions o;
    o.rate_hz = rates[i];
    o.duration = 1.2;
    err[i] =
        predictionError(tr, test::simulateImu(tr, o), ns(0.1), ns(1.1), ImuBias(), noise).velocity;
  }
  EXPECT_GT(err[0] / err[1], 10.0);
  EXPECT_LT(err[0] / err[1], 25.0);
}

// Preintegration + predict equals direct integration in the world frame
// (ImuPoseTable, same scheme), up to rounding.
TEST(ImuPreintegration, PredictEqualsDirectWorldFrameIntegration) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  test::ImuSimOptions o;
  o.white_noise = true;  // any signal will do
  o.bias.gyro = Eigen::Vector3d(0.003, 0.0, -0.002);
  const auto samples = test::simulateImu(tr, o);
  ImuBias bias;
  bias.gyro = Eigen::Vector3d(0.001, 0.002, 0.003);
  bias.accel = Eigen::Vector3d(-0.05, 0.02, 0.1);
  const std::int64_t t_i = ns(0.30001), t_j = ns(0.40377);
  const ImuState start = tr.state(t_i, bias);
  const ImuPreintegration pre = ImuPreintegration::fromSamples(samples, t_i, t_j, bias, ImuNoise());
  const ImuState a = pre.predict(start);
  const ImuState b = ImuPoseTable::fromSamples(start, samples, t_j, 9.81).endState();
  EXPECT_EQ(a.stamp_ns, t_j);
  EXPECT_EQ(b.stamp_ns, t_j);
  EXPECT_LT(angleBetween(a.T_world_imu.rotation(), b.T_world_imu.rotation()), 1e-12);
  EXPECT_LT((a.v_world_imu - b.v_world_imu).norm(), 1e-12);
  EXPECT_LT((a.T_world_imu.translation() - b.T_world_imu.translation()).norm(), 1e-12);
}

// Samples removed before one (ImuSample::after_removed: a saturated run,
// io/imu_guard.h) make its interval a dropout whatever its length: the
// covariance grows by the dropout sigmas there; the mean is unchanged.
TEST(ImuPreintegration, AnIntervalAfterRemovedSamplesIsADropout) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  auto samples = test::simulateImu(tr, test::ImuSimOptions());
  const std::int64_t t_i = ns(0.30001), t_j = ns(0.40377);
  // 20 ms without samples (below the 50 ms dropout threshold).
  const auto in_hole = [&](const ImuSample& s) {
    return s.stamp_ns > ns(0.35) && s.stamp_ns < ns(0.37);
  };
  samples.erase(std::remove_if(samples.begin(), samples.end(), in_hole), samples.end());
  const auto after = std::find_if(samples.begin(), samples.end(),
                                  [&](const ImuSample& s) { return s.stamp_ns >= ns(0.37); });
  ASSERT_NE(after, samples.end());
  const ImuPreintegration plain =
      ImuPreintegration::fromSamples(samples, t_i, t_j, ImuBias(), ImuNoise());
  after->after_removed = true;
  const ImuPreintegration marked =
      ImuPreintegration::fromSamples(samples, t_i, t_j, ImuBias(), ImuNoise());
  EXPECT_LT((plain.predict(tr.state(t_i, ImuBias())).T_world_imu.translation() -
             marked.predict(tr.state(t_i, ImuBias())).T_world_imu.translation())
                .norm(),
            1e-15);
  // Over the 20 ms hole the rotation's variance grows by about
  // dropout_gyro_density^2 dt = (0.3 rad/s/sqrt(Hz))^2 (0.02 s) per axis.
  const double added = marked.covariance()(0, 0) - plain.covariance()(0, 0);
  EXPECT_GT(added, 0.5 * 1.8e-3);
  EXPECT_LT(added, 2.0 * 1.8e-3);
}

// Filled samples (ImuSample::filled, odometry/imu_gap_fill.h) make the
// intervals to and from them dropouts: over 0.1 s of them the rotation's
// variance grows by about dropout_gyro_density^2 * 0.1 s per axis.
TEST(ImuPreintegration, IntervalsOfFilledSamplesAreDropouts) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  auto samples = test::simulateImu(tr, test::ImuSimOptions());
  const std::int64_t t_i = ns(0.30001), t_j = ns(0.50377);
  const ImuPreintegration plain =
      ImuPreintegration::fromSamples(samples, t_i, t_j, ImuBias(), ImuNoise());
  for (ImuSample& s : samples)
    if (s.stamp_ns > ns(0.35) && s.stamp_ns < ns(0.45)) s.filled = true;
  const ImuPreintegration marked =
      ImuPreintegration::fromSamples(samples, t_i, t_j, ImuBias(), ImuNoise());
  EXPECT_LT((plain.deltas().dp - marked.deltas().dp).norm(), 1e-15);
  const double added = marked.covariance()(0, 0) - plain.covariance()(0, 0);
  EXPECT_GT(added, 0.8 * 0.09 * 0.1);
  EXPECT_LT(added, 1.25 * 0.09 * 0.1);
}

// Analytic bias Jacobians against central differences of full re-integration.
TEST(ImuPreintegration, BiasJacobiansMatchFiniteDifferences) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  test::ImuSimOptions o;
  o.duration = 0.6;
  const auto samples = test::simulateImu(tr, o);
  ImuBias bias;
  bias.gyro = Eigen::Vector3d(0.02, -0.01, 0.015);
  bias.accel = Eigen::Vector3d(0.1, -0.2, 0.05);
  const ImuPreintegration pre =
      ImuPreintegration::fromSamples(samples, ns(0.0512), ns(0.5512), bias, ImuNoise());
  const double h = 1e-6;
  Eigen::Matrix<double, 9, 6> numeric;
  for (int c = 0; c < 6; ++c) {
    ImuBias plus = bias, minus = bias;
    (c < 3 ? plus.gyro : plus.accel)(c % 3) += h;
    (c < 3 ? minus.gyro : minus.accel)(c % 3) -= h;
    ImuPreintegration p_plus = pre, p_minus = pre;
    p_plus.repropagate(plus);
    p_minus.repropagate(minus);
    numeric.block<3, 1>(0, c) =
        (so3::logQuaternion(pre.deltas().dR.conjugate() * p_plus.deltas().dR) -
         so3::logQuaternion(pre.deltas().dR.conjugate() * p_minus.deltas().dR)) /
        (2 * h);
    numeric.block<3, 1>(3, c) = (p_plus.deltas().dv - p_minus.deltas().dv) / (2 * h);
    numeric.block<3, 1>(6, c) = (p_plus.deltas().dp - p_minus.deltas().dp) / (2 * h);
  }
  Eigen::Matrix<double, 9, 6> analytic = Eigen::Matrix<double, 9, 6>::Zero();
  analytic.block<3, 3>(0, 0) = pre.dR_dbg();
  analytic.block<3, 3>(3, 0) = pre.dv_dbg();
  analytic.block<3, 3>(3, 3) = pre.dv_dba();
  analytic.block<3, 3>(6, 0) = pre.dp_dbg();
  analytic.block<3, 3>(6, 3) = pre.dp_dba();
  // Fixture check: every Jacobian block that should be non-zero is.
  EXPECT_GT(pre.dR_dbg().norm(), 0.4);
  EXPECT_GT(pre.dv_dbg().norm(), 0.05);
  EXPECT_GT(pre.dp_dbg().norm(), 0.01);
  const double rel = (analytic - numeric).norm() / numeric.norm();
  std::cout << "[ measured ] bias Jacobian relative error " << rel << "\n";
  EXPECT_LT(rel, 1e-7) << "analytic\n" << analytic << "\nnumeric\n" << numeric;
  // The accel bias enters linearly: dv/dba = -sum dR_k dt, at t->0 about -Dt I.
  EXPECT_LT((pre.dv_dba() + 0.5 * Eigen::Matrix3d::Identity()).norm(), 0.5);
}

// First-order correction against re-integration for bias changes of the
// size the odometry sees between re-integrations; accel exact.
TEST(ImuPreintegration, FirstOrderBiasCorrectionMatchesReintegration) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  test::ImuSimOptions o;
  o.duration = 0.3;
  const auto samples = test::simulateImu(tr, o);
  const ImuBias bias0;
  const ImuPreintegration pre =
      ImuPreintegration::fromSamples(samples, ns(0.1), ns(0.2), bias0, ImuNoise());
  const ImuPreintegrationConfig config;
  ImuBias bias1;
  bias1.gyro = Eigen::Vector3d(1, -1, 0.5).normalized() * config.repropagate_gyro_bias_change;
  bias1.accel = Eigen::Vector3d(-1, 0.3, 0.7).normalized() * config.repropagate_accel_bias_change;
  ImuPreintegration exact = pre;
  exact.repropagate(bias1);
  const ImuDeltas corrected = pre.correctedDeltas(bias1);
  const double rot_err = angleBetween(corrected.dR, exact.deltas().dR);
  const double vel_err = (corrected.dv - exact.deltas().dv).norm();
  const double pos_err = (corrected.dp - exact.deltas().dp).norm();
  std::cout << "[ measured ] first-order correction at the repropagation thresholds over 0.1 s: "
            << rot_err << " rad, " << vel_err << " m/s, " << pos_err << " m\n";
  EXPECT_LT(rot_err, 1e-6);
  EXPECT_LT(vel_err, 1e-5);
  EXPECT_LT(pos_err, 1e-6);
  EXPECT_GT(angleBetween(pre.deltas().dR, exact.deltas().dR), 5e-4);  // the change is not trivial

  ImuBias accel_only = bias0;
  accel_only.accel = Eigen::Vector3d(0.3, -0.2, 0.1);
  ImuPreintegration exact_a = pre;
  exact_a.repropagate(accel_only);
  EXPECT_LT((pre.correctedDeltas(accel_only).dv - exact_a.deltas().dv).norm(), 1e-13);
  EXPECT_LT((pre.correctedDeltas(accel_only).dp - exact_a.deltas().dp).norm(), 1e-13);

  EXPECT_FALSE(pre.needsRepropagation(bias0, config));
  ImuBias big = bias1;
  big.gyro *= 1.01;
  EXPECT_TRUE(pre.needsRepropagation(big, config));
}

// Predicted covariance against Monte-Carlo: errors of noisy preintegrations
// relative to the noise-free one (same biases), bias random walk on. Checks
// each standard deviation (within 12 %) and the mean Mahalanobis distance
// (chi-square with 15 dof: mean 15, std of the mean sqrt(30 / N)).
TEST(ImuPreintegration, CovarianceMatchesMonteCarlo) {
  const SyntheticTrajectory tr = SyntheticTrajectory::trot();
  ImuNoise noise;
  noise.gyro_random_walk = 2e-3;  // large, so the bias rows and their correlations matter
  noise.accel_random_walk = 2e-2;
  const std::int64_t t_i = ns(0.0), t_j = ns(0.5);
  test::ImuSimOptions o;
  o.duration = 0.5;
  o.noise = noise;
  const auto clean = test::simulateImu(tr, o);
  const ImuBias bias0;
  const ImuPreintegration ref = ImuPreintegration::fromSamples(clean, t_i, t_j, bias0, noise);
  const Matrix15d& Sigma = ref.covariance();
  const Eigen::LLT<Matrix15d> llt(Sigma);
  ASSERT_EQ(llt.info(), Eigen::Success);

  const int runs = 1500;
  Eigen::Matrix<double, 15, Eigen::Dynamic> errors(15, runs);
  o.white_noise = true;
  o.bias_walk = true;
  double mahalanobis = 0.0;
  for (int r = 0; r < runs; ++r) {
    o.seed = 100 + static_cast<std::uint32_t>(r);
    std::vector<ImuBias> biases;
    const auto noisy = test::simulateImu(tr, o, &biases);
    // Integrate with the bias at t_i (here zero): its drift is part of the error.
    const ImuPreintegration pre = ImuPreintegration::fromSamples(noisy, t_i, t_j, bias0, noise);
    Eigen::Matrix<double, 15, 1> e;
    e.segment<3>(0) = so3::logQuaternion(ref.deltas().dR.conjugate() * pre.deltas().dR);
    e.segment<3>(3) = pre.deltas().dv - ref.deltas().dv;
    e.segment<3>(6) = pre.deltas().dp - ref.deltas().dp;
    // Residual convention: measurement minus truth for all 15 (bias: b_i - b_j).
    e.segment<3>(9) = biases.front().gyro - biases.back().gyro;
    e.segment<3>(12) = biases.front().accel - biases.back().accel;
    errors.col(r) = e;
    mahalanobis += e.dot(llt.solve(e));
  }
  mahalanobis /= runs;
  const Matrix15d sample = errors * errors.transpose() / runs;
  std::cout << "[ measured ] Monte-Carlo mean Mahalanobis " << mahalanobis << " (expected 15)\n";
  std::cout << "[ measured ] std ratio (sample / predicted):";
  for (int i = 0; i < 15; ++i) {
    const double ratio = std::sqrt(sample(i, i) / Sigma(i, i));
    std::cout << " " << ratio;
    EXPECT_NEAR(ratio, 1.0, 0.12) << "row " << i;
  }
  std::cout << "\n";
  EXPECT_NEAR(mahalanobis, 15.0, 1.2);
  // The correlations the model predicts (e.g. velocity with gyro bias drift) are real:
  // whitened sample covariance close to identity.
  const Eigen::Matrix<double, 15, 15> L_inv = llt.matrixL().solve(Matrix15d::Identity());
  const Matrix15d whitened = L_inv * sample * L_inv.transpose();
  EXPECT_LT((whitened - Matrix15d::Identity()).cwiseAbs().maxCoeff(), 0.2);
}

TEST(ImuPreintegration, RejectsBadNoise) {
  ImuSignal s;
  s.knots.resize(2);
  s.knots[1].t = 0.01;
  ImuNoise bad;
  bad.gyro_noise_density = -1;
  EXPECT_THROW((ImuPreintegration{s, ImuBias(), bad}), Error);
  s.knots[1].t = 0.0;
  EXPECT_THROW((ImuPreintegration{s, ImuBias(), ImuNoise()}), Error);
}

}  // namespace
}  // namespace storey
