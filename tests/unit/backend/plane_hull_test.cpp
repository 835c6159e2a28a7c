// The outline of a plane patch (planes.json "hull"): the convex hull of the
// inliers projected on the plane, counter-clockwise seen from the normal,
// simplified to at most max_vertices by dropping the least-area vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "backend/plane_hull.h"

namespace storey::backend {
namespace {

double signedAreaSeenFrom(const std::vector<Eigen::Vector3d>& polygon, const Eigen::Vector3d& n) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i)
    sum += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  return 0.5 * sum.dot(n);
}

TEST(PlaneHull, RectangleOnATiltedPlaneGivesItsFourCornersOnThePlane) {
  // A 3 m x 2 m rectangle on the plane x = 4 (normal +x), filled with points
  // 1 cm off the plane either side.
  const Plane plane(Eigen::Vector3d::UnitX(), 4.0);
  std::vector<Eigen::Vector3d> points;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> off(-0.01, 0.01);
  for (int i = 0; i <= 30; ++i)
    for (int j = 0; j <= 20; ++j) points.emplace_back(4.0 + off(rng), -1.0 + 0.1 * i, 0.1 * j);
  const auto hull = planeHull(points, plane, 16);
  ASSERT_EQ(hull.size(), 4u);
  for (const auto& v : hull) {
    EXPECT_NEAR(v.x(), 4.0, 1e-9) << "vertices lie on the plane";
    EXPECT_TRUE(std::abs(v.y() + 1.0) < 1e-9 || std::abs(v.y() - 2.0) < 1e-9);
    EXPECT_TRUE(std::abs(v.z()) < 1e-9 || std::abs(v.z() - 2.0) < 1e-9);
  }
  EXPECT_NEAR(signedAreaSeenFrom(hull, plane.normal()), 6.0, 1e-9) << "counter-clockwise from +n";
}

TEST(PlaneHull, DiscIsSimplifiedToTheVertexLimitKeepingMostOfTheArea) {
  const Plane plane(Eigen::Vector3d(0, 0, 1), 0.5);  // floor z = 0.5
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 360; ++k) {
    const double a = k * M_PI / 180.0;
    points.emplace_back(2.0 * std::cos(a), 2.0 * std::sin(a), 0.5);
  }
  points.emplace_back(0, 0, 0.5);  // interior point
  const auto hull = planeHull(points, plane, 12);
  ASSERT_EQ(hull.size(), 12u);
  const double area = signedAreaSeenFrom(hull, plane.normal());
  // A regular 12-gon in a circle of radius 2 has 3 r^2 = 12 m^2 (circle: 12.57).
  EXPECT_GT(area, 11.5);
  EXPECT_LT(area, 4.0 * M_PI);
}

TEST(PlaneHull, DegenerateInputGivesNoHull) {
  const Plane plane(Eigen::Vector3d::UnitZ(), 0.0);
  EXPECT_TRUE(planeHull({}, plane).empty());
  EXPECT_TRUE(planeHull({{0, 0, 0}, {1, 0, 0}}, plane).empty());
  EXPECT_TRUE(planeHull({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, plane).empty()) << "collinear";
}

TEST(PlaneHull, ConvexHullOfManyPointsKeepsEveryPointInsideAndOnlyInputVertices) {
  // Thousands of points (a scan plane's inliers): the interior-point filter
  // before the sort must drop no hull vertex. Shapes whose extreme points
  // coincide in several directions (axis-aligned and rotated rectangles, a
  // disc, a thin band, a triangle) and points on the hull's edges.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto rotate = [](const Eigen::Vector2d& q, double angle) {
    return Eigen::Vector2d(std::cos(angle) * q.x() - std::sin(angle) * q.y(),
                           std::sin(angle) * q.x() + std::cos(angle) * q.y());
  };
  for (int shape = 0; shape < 6; ++shape) {
    std::vector<Eigen::Vector2d> points;
    for (int i = 0; i < 5000; ++i) {
      const double u = unit(rng), v = unit(rng);
      Eigen::Vector2d q;
      if (shape == 0) q = {6.0 * u, 2.0 * v};                               // axis-aligned
      if (shape == 1) q = rotate({6.0 * u, 2.0 * v}, 0.3);                  // rotated
      if (shape == 2) q = rotate({3.0, 0.0}, 2 * M_PI * u) * std::sqrt(v);  // disc
      if (shape == 3) q = rotate({20.0 * u, 0.05 * v}, 0.785398);           // thin diagonal band
      if (shape == 4) q = {u * 4.0, (1.0 - u) * v * 3.0};                   // triangle
      if (shape == 5) q = {std::round(10.0 * u) * 0.5, std::round(10.0 * v) * 0.5};  // grid
      points.push_back(q + Eigen::Vector2d(100.0, -50.0));
    }
    const std::vector<Eigen::Vector2d> hull = convexHull(points);
    ASSERT_GE(hull.size(), 3u) << "shape " << shape;
    for (const Eigen::Vector2d& vertex : hull)
      EXPECT_NE(std::find(points.begin(), points.end(), vertex), points.end()) << "shape " << shape;
    for (std::size_t e = 0; e < hull.size(); ++e) {
      const Eigen::Vector2d& o = hull[e];
      const Eigen::Vector2d& t = hull[(e + 1) % hull.size()];
      const Eigen::Vector2d& next = hull[(e + 2) % hull.size()];
      const auto cross = [&](const Eigen::Vector2d& q) {
        return (t - o).x() * (q - o).y() - (t - o).y() * (q - o).x();
      };
      EXPECT_GT(cross(next), 0.0) << "shape " << shape << ": not strictly convex at " << e;
      double worst = 0.0;
      for (const Eigen::Vector2d& q : points) worst = std::min(worst, cross(q));
      EXPECT_GE(worst, -1e-9) << "shape " << shape << ": a point outside edge " << e;
    }
    if (shape == 5) {
      EXPECT_EQ(hull.size(), 4u);
    }
  }
}

}  // namespace
}  // namespace storey::backend
