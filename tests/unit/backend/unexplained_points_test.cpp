#include "backend/unexplained_points.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <vector>

namespace storey::backend {
namespace {

/// The inlier test the float pre-test must reproduce exactly.
bool insideInDouble(const Eigen::Vector3f& p, const Eigen::Vector3d& n, double d,
                    double threshold) {
  const Eigen::Vector3d q = p.cast<double>();
  return std::abs((n.x() * q.x() + n.y() * q.y()) + n.z() * q.z() - d) <= threshold;
}

/// Points at up to 100 m whose distances to the plane n.p = d cluster within
/// a few float roundings of +-threshold, where a float test alone would
/// decide some of them the other way.
std::vector<Eigen::Vector3f> pointsAtTheThreshold(const Eigen::Vector3d& n, double d,
                                                  double threshold, std::mt19937& rng) {
  std::uniform_real_distribution<double> coordinate(-100.0, 100.0);
  std::uniform_real_distribution<double> offset(-2e-5, 2e-5);
  std::uniform_int_distribution<int> side(0, 1);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d p(coordinate(rng), coordinate(rng), coordinate(rng));
    const double target = (side(rng) ? threshold : -threshold) + offset(rng);
    points.push_back((p + (target - (n.dot(p) - d)) * n).cast<float>());
  }
  return points;
}

TEST(UnexplainedPoints, InliersAreExactlyTheDoubleTestsAtTheThreshold) {
  std::mt19937 rng(7);
  const double threshold = 0.05;
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.5, 0.81).normalized();
  const double d = 37.25;
  const std::vector<Eigen::Vector3f> points = pointsAtTheThreshold(n, d, threshold, rng);

  std::vector<std::uint32_t> expected;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (insideInDouble(points[i], n, d, threshold))
      expected.push_back(static_cast<std::uint32_t>(i));
  // The case is a real one: about half inside, and a float-only test would
  // differ on some points.
  ASSERT_GT(expected.size(), points.size() / 4);
  ASSERT_LT(expected.size(), 3 * points.size() / 4);
  const Eigen::Vector3f nf = n.cast<float>();
  int float_disagrees = 0;
  for (const Eigen::Vector3f& p : points) {
    const float distance =
        std::abs((nf.x() * p.x() + nf.y() * p.y()) + nf.z() * p.z() - static_cast<float>(d));
    if ((distance <= static_cast<float>(threshold)) != insideInDouble(p, n, d, threshold))
      ++float_disagrees;
  }
  EXPECT_GT(float_disagrees, 0);

  const UnexplainedPoints unexplained(points);
  std::vector<std::uint32_t> within;
  unexplained.within(n, d, threshold, within);
  EXPECT_EQ(within, expected);
}

TEST(UnexplainedPoints, ExtractRemovesExactlyTheInliersAndKeepsTheOrder) {
  std::mt19937 rng(11);
  const double threshold = 0.05;
  const Eigen::Vector3d n = Eigen::Vector3d(-0.2, 0.1, 1.0).normalized();
  const double d = 2.5;
  std::vector<Eigen::Vector3f> points = pointsAtTheThreshold(n, d, threshold, rng);
  // Blocks with no inlier at all, between blocks with some: far points.
  for (int i = 0; i < 3000; ++i) points.push_back((5.0 * n * (d + 1.0 + i * 1e-3)).cast<float>());
  const std::vector<Eigen::Vector3f> more = pointsAtTheThreshold(n, d, threshold, rng);
  points.insert(points.end(), more.begin(), more.end());

  UnexplainedPoints unexplained(points);
  std::vector<Eigen::Vector3d> inliers;
  std::vector<std::uint32_t> inlier_index;
  unexplained.extract(n, d, threshold, inliers, inlier_index);

  std::vector<std::uint32_t> expected_in, expected_out;
  for (std::size_t i = 0; i < points.size(); ++i)
    (insideInDouble(points[i], n, d, threshold) ? expected_in : expected_out)
        .push_back(static_cast<std::uint32_t>(i));
  EXPECT_EQ(inlier_index, expected_in);
  ASSERT_EQ(inliers.size(), expected_in.size());
  for (std::size_t k = 0; k < inliers.size(); ++k)
    EXPECT_EQ(inliers[k], points[expected_in[k]].cast<double>());
  EXPECT_EQ(unexplained.index, expected_out);
  for (std::size_t k = 0; k < expected_out.size(); ++k) {
    const Eigen::Vector3f& p = points[expected_out[k]];
    EXPECT_EQ(unexplained.x[k], p.x());
    EXPECT_EQ(unexplained.y[k], p.y());
    EXPECT_EQ(unexplained.z[k], p.z());
  }
}

}  // namespace
}  // namespace storey::backend
