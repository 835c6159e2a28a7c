#include "odometry/state_prior.h"

#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "../imu/synthetic_imu.h"
#include "imu/imu_state_blocks.h"
#include "imu/so3.h"

namespace storey {
namespace {

std::int64_t ns(double seconds) {
  return test::kBaseNs + secondsToNs(seconds);
}

StatePrior randomPrior(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  StatePrior prior;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  const double pose[7] = {n(rng), n(rng), n(rng), q.x(), q.y(), q.z(), q.w()};
  std::copy(pose, pose + 7, prior.pose);
  for (int k = 0; k < 11; ++k) prior.motion_tilt(k) = 0.1 * n(rng);
  Matrix17d A;
  for (int r = 0; r < 17; ++r)
    for (int c = 0; c < 17; ++c) A(r, c) = n(rng);
  prior.information = A * A.transpose() + 17.0 * Matrix17d::Identity();
  return prior;
}

TEST(StatePrior, JacobiansMatchNumericDifferentiation) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 0.05);
  for (int trial = 0; trial < 5; ++trial) {
    const StatePrior prior = randomPrior(rng);
    const StatePriorFactor factor(prior);
    // Away from the mean (also with q on the far sign branch).
    std::array<double, 7> pose;
    Eigen::Quaterniond q =
        so3::expQuaternion(Eigen::Vector3d(n(rng), n(rng), n(rng))) *
        Eigen::Quaterniond(prior.pose[6], prior.pose[3], prior.pose[4], prior.pose[5]);
    if (trial % 2 == 1) q.coeffs() = -q.coeffs();
    pose = {prior.pose[0] + n(rng),
            prior.pose[1] + n(rng),
            prior.pose[2] + n(rng),
            q.x(),
            q.y(),
            q.z(),
            q.w()};
    std::array<double, 9> motion;
    std::array<double, 2> tilt;
    for (int k = 0; k < 9; ++k) motion[k] = prior.motion_tilt(k) + n(rng);
    for (int k = 0; k < 2; ++k) tilt[k] = prior.motion_tilt(9 + k) + n(rng);
    ImuPoseManifold pose_manifold;
    std::vector<const ceres::Manifold*> manifolds{&pose_manifold, nullptr, nullptr};
    ceres::NumericDiffOptions options;
    ceres::GradientChecker checker(&factor, &manifolds, options);
    ceres::GradientChecker::ProbeResults results;
    double* parameters[] = {pose.data(), motion.data(), tilt.data()};
    EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results)) << results.error_log;
  }
}

TEST(StatePrior, ResidualIsTheWhitenedTangentStep) {
  std::mt19937 rng(3);
  const StatePrior prior = randomPrior(rng);
  const StatePriorFactor factor(prior);
  // x = Plus(mean, step) on the pose manifold: r = S step to first order.
  Vector17d step;
  for (int k = 0; k < 17; ++k) step(k) = 1e-4 * (k + 1) * (k % 2 ? -1 : 1);
  ImuPoseManifold manifold;
  double pose[7];
  manifold.Plus(prior.pose, step.data(), pose);
  double motion[9], tilt[2];
  for (int k = 0; k < 9; ++k) motion[k] = prior.motion_tilt(k) + step(6 + k);
  for (int k = 0; k < 2; ++k) tilt[k] = prior.motion_tilt(9 + k) + step(15 + k);
  const double* parameters[] = {pose, motion, tilt};
  Vector17d r;
  factor.Evaluate(parameters, r.data(), nullptr);
  // 0.5 r^T r against 0.5 step^T Lambda step.
  const double expected = step.dot(prior.information * step);
  EXPECT_NEAR(r.squaredNorm(), expected, 1e-6 * expected);
  // And zero at the mean.
  double motion0[9], tilt0[2];
  for (int k = 0; k < 9; ++k) motion0[k] = prior.motion_tilt(k);
  for (int k = 0; k < 2; ++k) tilt0[k] = prior.motion_tilt(9 + k);
  const double* at_mean[] = {prior.pose, motion0, tilt0};
  factor.Evaluate(at_mean, r.data(), nullptr);
  EXPECT_LT(r.norm(), 1e-9);
}

/// Three states of the synthetic trot, 0.1 s apart, and the IMU factors between them.
struct Chain {
  test::SyntheticTrajectory trajectory = test::SyntheticTrajectory::trot();
  std::vector<ImuSample> samples;
  std::vector<ImuStateBlocks> states;
  std::vector<ImuPreintegration> preintegrations;
  double tilt[2] = {0.001, -0.002};
  Chain() {
    test::ImuSimOptions options;
    samples = test::simulateImu(trajectory, options);
    for (int k = 0; k < 3; ++k)
      states.push_back(ImuStateBlocks::fromState(trajectory.state(ns(0.5 + 0.1 * k))));
    for (int k = 0; k < 2; ++k)
      preintegrations.push_back(ImuPreintegration::fromSamples(
          samples, ns(0.5 + 0.1 * k), ns(0.6 + 0.1 * k), ImuBias(), ImuNoise()));
  }
};

Eigen::Matrix<double, 6, 6> lidarInformation(double sigma_position, double sigma_rotation) {
  Eigen::Matrix<double, 6, 1> d;
  d << Eigen::Vector3d::Constant(1.0 / (sigma_position * sigma_position)),
      Eigen::Vector3d::Constant(1.0 / (sigma_rotation * sigma_rotation));
  return d.asDiagonal();
}

// Two steps of the recursion are the Schur complement of the batch problem
// over all three states (the same linearisation points, so exactly, up to
// rounding): the index bookkeeping of the marginalisation is right.
TEST(StatePrior, TwoStepsEqualTheBatchMarginal) {
  const Chain chain;
  std::mt19937 rng(11);
  for (bool anchored : {true, false}) {
    StatePrior prior_0 = randomPrior(rng);
    std::copy(chain.states[0].pose, chain.states[0].pose + 7, prior_0.pose);
    MotionPrior motion_prior_0;
    motion_prior_0.information = prior_0.information.bottomRightCorner<11, 11>();
    const Eigen::Matrix<double, 6, 6> L0 = lidarInformation(0.01, 0.002);
    const Eigen::Matrix<double, 6, 6> L1 = lidarInformation(0.02, 0.004);

    const StatePrior prior_1 = propagateStatePrior(
        anchored ? nullptr : &prior_0, motion_prior_0, ImuGravityFactor(chain.preintegrations[0]),
        chain.states[0].pose, chain.states[0].motion, chain.states[1].pose, chain.states[1].motion,
        chain.tilt, L0);
    const StatePrior prior_2 = propagateStatePrior(
        &prior_1, motion_prior_0, ImuGravityFactor(chain.preintegrations[1]), chain.states[1].pose,
        chain.states[1].motion, chain.states[2].pose, chain.states[2].motion, chain.tilt, L1);

    // Batch: z = [x_0 (15), x_1 (15), x_2 (15), tilt (2)], x = [pose (6), motion (9)].
    Eigen::Matrix<double, 47, 47> H = Eigen::Matrix<double, 47, 47>::Zero();
    for (int a = 0; a < 2; ++a) {
      const ImuStateBlocks& s = chain.states[static_cast<std::size_t>(a)];
      const ImuStateBlocks& t = chain.states[static_cast<std::size_t>(a + 1)];
      const Eigen::Matrix<double, 32, 32> h =
          imuFactorInformation(ImuGravityFactor(chain.preintegrations[static_cast<std::size_t>(a)]),
                               s.pose, s.motion, t.pose, t.motion, chain.tilt);
      std::vector<int> index;
      for (int k = 0; k < 30; ++k) index.push_back(15 * a + k);
      index.push_back(45);
      index.push_back(46);
      for (int r = 0; r < 32; ++r)
        for (int c = 0; c < 32; ++c)
          H(index[static_cast<std::size_t>(r)], index[static_cast<std::size_t>(c)]) += h(r, c);
    }
    std::vector<int> prior_index;
    for (int k = 0; k < 15; ++k) prior_index.push_back(k);
    prior_index.push_back(45);
    prior_index.push_back(46);
    for (int r = anchored ? 6 : 0; r < 17; ++r)
      for (int c = anchored ? 6 : 0; c < 17; ++c)
        H(prior_index[static_cast<std::size_t>(r)], prior_index[static_cast<std::size_t>(c)]) +=
            prior_0.information(r, c);
    Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Identity();
    T.bottomRightCorner<3, 3>() *= 2.0;
    H.block<6, 6>(0, 0) += T.transpose() * L0 * T;
    H.block<6, 6>(15, 15) += T.transpose() * L1 * T;
    // An anchored pose_0 is known: not a variable.
    const int first = anchored ? 6 : 0;
    const Eigen::MatrixXd A = H.block(first, first, 30 - first, 30 - first);
    const Eigen::MatrixXd B = H.block(first, 30, 30 - first, 17);
    const Matrix17d expected = H.bottomRightCorner<17, 17>() - B.transpose() * A.ldlt().solve(B);

    EXPECT_LT((prior_2.information - expected).norm(), 1e-6 * expected.norm())
        << (anchored ? "anchored" : "with a prior on pose_0");
    for (int k = 0; k < 7; ++k) EXPECT_EQ(prior_2.pose[k], chain.states[2].pose[k]);
  }
}

// What the change is for: with the LiDAR's information on every pose, the
// velocity is known far better after a few seconds than any one pair of poses
// tells (the old motion prior treated each pair as new, with 2 cm a pose).
TEST(StatePrior, VelocityInformationAccumulatesOverTheScans) {
  const test::SyntheticTrajectory trajectory = test::SyntheticTrajectory::trot();
  test::ImuSimOptions options;
  options.duration = 5.0;
  const std::vector<ImuSample> samples = test::simulateImu(trajectory, options);
  const double tilt[2] = {0.0, 0.0};
  MotionPrior start;
  start.information = Matrix11d::Identity();  // 1 m/s, 1 rad/s, ... : nothing known
  StatePrior prior;
  MotionPrior motion_prior = start;
  bool anchored = true;
  const Eigen::Matrix<double, 6, 6> L = lidarInformation(0.01, 0.002);
  for (int k = 0; k < 40; ++k) {
    const ImuStateBlocks s = ImuStateBlocks::fromState(trajectory.state(ns(0.2 + 0.1 * k)));
    const ImuStateBlocks t = ImuStateBlocks::fromState(trajectory.state(ns(0.3 + 0.1 * k)));
    const ImuPreintegration pre = ImuPreintegration::fromSamples(
        samples, ns(0.2 + 0.1 * k), ns(0.3 + 0.1 * k), ImuBias(), ImuNoise());
    const ImuGravityFactor factor(pre);
    prior = propagateStatePrior(anchored ? nullptr : &prior, start, factor, s.pose, s.motion,
                                t.pose, t.motion, tilt, L);
    motion_prior = propagateMotionPrior(motion_prior, factor, s.pose, s.motion, t.pose, t.motion,
                                        tilt, 0.02, 0.005);
    anchored = false;
  }
  const Matrix17d covariance = prior.information.inverse();
  const Matrix11d motion_covariance = motion_prior.information.inverse();
  const double sigma_vz = std::sqrt(covariance(8, 8));
  const double sigma_vz_pose_sigmas = std::sqrt(motion_covariance(2, 2));
  // 1 cm a scan for 4 s, starting from nothing known (the accelerometer bias
  // included, which the velocity shares): a straight-line fit of the 40
  // positions alone would give 1.4 mm/s; measured 4.8 mm/s, against 9 cm/s
  // with the pose-sigma prior.
  EXPECT_LT(sigma_vz, 0.006) << sigma_vz_pose_sigmas;
  EXPECT_GT(sigma_vz_pose_sigmas, 5.0 * sigma_vz);
  // The position is held to about the LiDAR's centimetre, not beyond it by magic.
  EXPECT_GT(std::sqrt(covariance(2, 2)), 0.001);
  EXPECT_LT(std::sqrt(covariance(2, 2)), 0.01);
}

}  // namespace
}  // namespace storey
