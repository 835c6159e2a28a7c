#include "odometry/lidar_factors.h"

#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>
#include <gtest/gtest.h>

#include <random>

namespace storey {
namespace {

using PoseManifold =
    ceres::ProductManifold<ceres::EuclideanManifold<3>, ceres::EigenQuaternionManifold>;

std::array<double, 7> randomPose(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return {3 * n(rng), 3 * n(rng), 3 * n(rng), q.x(), q.y(), q.z(), q.w()};
}

void expectGradientsMatch(const ceres::CostFunction& factor, std::array<double, 7>& pose) {
  PoseManifold manifold;
  std::vector<const ceres::Manifold*> manifolds{&manifold};
  ceres::NumericDiffOptions options;
  ceres::GradientChecker checker(&factor, &manifolds, options);
  ceres::GradientChecker::ProbeResults results;
  double* parameters[] = {pose.data()};
  EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results)) << results.error_log;
}

TEST(LidarFactors, WorldPointMatchesPose) {
  std::mt19937 rng(11);
  for (int i = 0; i < 20; ++i) {
    auto pose = randomPose(rng);
    const Eigen::Vector3d y(1.0, -2.0, 0.5);
    Eigen::Vector3d x;
    worldPointJacobian(pose.data(), y, x, nullptr);
    const Eigen::Quaterniond q(pose[6], pose[3], pose[4], pose[5]);
    EXPECT_TRUE(x.isApprox(q * y + Eigen::Vector3d(pose[0], pose[1], pose[2]), 1e-12));
  }
}

TEST(LidarFactors, PointToPlaneJacobianMatchesNumeric) {
  std::mt19937 rng(12);
  for (int i = 0; i < 20; ++i) {
    auto pose = randomPose(rng);
    PointToPlaneFactor factor(Eigen::Vector3d(2.0, 1.0, -0.5),
                              Eigen::Vector3d(0.3, -0.5, 0.8).normalized(), 2.5, 20.0);
    expectGradientsMatch(factor, pose);
  }
}

TEST(LidarFactors, PointToLineJacobianMatchesNumeric) {
  std::mt19937 rng(13);
  for (int i = 0; i < 20; ++i) {
    auto pose = randomPose(rng);
    PointToLineFactor factor(Eigen::Vector3d(-1.0, 3.0, 0.2), Eigen::Vector3d(1.0, 2.0, 3.0),
                             Eigen::Vector3d(0.1, 0.2, 1.0), 10.0);
    expectGradientsMatch(factor, pose);
  }
}

TEST(LidarFactors, ResidualsAreWeightedDistances) {
  // Identity pose; the point (1, 2, 3) against the plane z = 1 and the x axis.
  std::array<double, 7> pose{0, 0, 0, 0, 0, 0, 1};
  const double* parameters[] = {pose.data()};
  double r1 = 0.0;
  PointToPlaneFactor plane(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d::UnitZ(), 1.0, 10.0);
  ASSERT_TRUE(plane.Evaluate(parameters, &r1, nullptr));
  EXPECT_NEAR(r1, 20.0, 1e-12);
  double r3[3];
  PointToLineFactor line(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(5, 0, 0),
                         Eigen::Vector3d::UnitX(), 2.0);
  ASSERT_TRUE(line.Evaluate(parameters, r3, nullptr));
  EXPECT_NEAR(Eigen::Map<Eigen::Vector3d>(r3).norm(), 2.0 * std::sqrt(13.0), 1e-12);
}

TEST(LidarFactors, HuberWeightIsOnTheWhitenedDistance) {
  // Identity pose; two points 0.05 m and 0.1 m above the plane z = 0, sigma 0.05:
  // whitened 1 (inside the Huber threshold 1.345) and 2 (weight 1.345 / 2).
  std::array<double, 7> pose{0, 0, 0, 0, 0, 0, 1};
  MatchResult matches;
  matches.planes.push_back({Eigen::Vector3d(0, 0, 0.05), Eigen::Vector3d::UnitZ(), 0.0, 0.05});
  matches.planes.push_back({Eigen::Vector3d(0, 0, 0.1), Eigen::Vector3d::UnitZ(), 0.0, 0.05});
  const ScanResidualsFactor factor(matches, pose.data(), 1.345);
  const double* parameters[] = {pose.data()};
  double r[2];
  ASSERT_TRUE(factor.Evaluate(parameters, r, nullptr));
  EXPECT_NEAR(r[0], 1.0, 1e-12);
  EXPECT_NEAR(r[1], std::sqrt(1.345 / 2.0) * 2.0, 1e-12);
  // The same distance with a 4x larger sigma (a thick fit) is not down-weighted.
  matches.planes[1].sigma = 0.2;
  const ScanResidualsFactor wide(matches, pose.data(), 1.345);
  ASSERT_TRUE(wide.Evaluate(parameters, r, nullptr));
  EXPECT_NEAR(r[1], 0.5, 1e-12);
}

TEST(LidarFactors, CompressedScanFactorHasTheSameNormalEquationsAndCost) {
  // In the manifold's tangent (what the solver sees): J^T J, J^T r and |r|^2
  // of the compressed factor's 8 rows equal those of one row per point.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    std::array<double, 7> pose = randomPose(rng);
    MatchResult matches;
    for (int i = 0; i < 300; ++i) {
      const Eigen::Vector3d y(5 * normal(rng), 5 * normal(rng), normal(rng));
      const Eigen::Vector3d n = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      matches.planes.push_back({y, n, 0.3 * normal(rng), 0.02 + 0.01 * std::abs(normal(rng))});
    }
    for (int i = 0; i < 20; ++i)
      matches.lines.push_back({Eigen::Vector3d(4 * normal(rng), 4 * normal(rng), normal(rng)),
                               Eigen::Vector3d(normal(rng), normal(rng), normal(rng)),
                               Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized(),
                               0.05});
    std::array<double, 7> weights_at = pose;
    weights_at[0] += 0.05;  // robust weights from a nearby pose, as in a solve
    const ScanResidualsFactor rows(matches, weights_at.data(), 1.345);
    const CompressedScanFactor compressed(matches, weights_at.data(), 1.345);
    const int n_rows = rows.num_residuals();
    ASSERT_EQ(n_rows, 300 + 3 * 20);
    const double* parameters[] = {pose.data()};
    Eigen::VectorXd r(n_rows);
    Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor> J(n_rows, 7);
    double* jacobians[] = {J.data()};
    ASSERT_TRUE(rows.Evaluate(parameters, r.data(), jacobians));
    Eigen::Matrix<double, 8, 1> rc;
    Eigen::Matrix<double, 8, 7, Eigen::RowMajor> Jc;
    double* jacobians_c[] = {Jc.data()};
    ASSERT_TRUE(compressed.Evaluate(parameters, rc.data(), jacobians_c));

    PoseManifold manifold;
    Eigen::Matrix<double, 7, 6, Eigen::RowMajor> P;
    ASSERT_TRUE(manifold.PlusJacobian(pose.data(), P.data()));
    const Eigen::MatrixXd Jt = J * P, Jct = Jc * P;
    const Eigen::MatrixXd H = Jt.transpose() * Jt, Hc = Jct.transpose() * Jct;
    const Eigen::VectorXd g = Jt.transpose() * r, gc = Jct.transpose() * rc;
    EXPECT_LT((H - Hc).norm(), 1e-9 * H.norm()) << "trial " << trial;
    EXPECT_LT((g - gc).norm(), 1e-9 * g.norm()) << "trial " << trial;
    EXPECT_NEAR(rc.squaredNorm(), r.squaredNorm(), 1e-9 * r.squaredNorm()) << "trial " << trial;
    // Cost alone (the step test).
    Eigen::Matrix<double, 8, 1> cost_only;
    ASSERT_TRUE(compressed.Evaluate(parameters, cost_only.data(), nullptr));
    EXPECT_NEAR(cost_only.squaredNorm(), r.squaredNorm(), 1e-9 * r.squaredNorm());
  }
}

}  // namespace
}  // namespace storey
