#include "odometry/lidar_factors.h"

#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>
#include <gtest/gtest.h>

#include <random>

namespace storey {
namespace {

using PoseManifold = ceres::ProductManifold<ceres::EuclideanManifold<3>, ceres::EigenQuaternionManifold>;

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
  PointToLineFactor line(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(5, 0, 0), Eigen::Vector3d::UnitX(), 2.0);
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

}  // namespace
}  // namespace storey
