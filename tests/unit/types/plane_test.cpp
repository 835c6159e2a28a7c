#include "types/plane.h"

#include <gtest/gtest.h>

#include <random>

#include "common/error.h"

namespace storey {
namespace {

TEST(Plane, NormalisedAndDistanceNonNegative) {
  const Plane p(Eigen::Vector3d(0, 0, -2), 4.0);  // -2z = 4  <=>  z = -2  <=>  -z = 2
  EXPECT_NEAR(p.normal().norm(), 1.0, 1e-15);
  EXPECT_GE(p.distance(), 0.0);
  EXPECT_TRUE(p.normal().isApprox(Eigen::Vector3d(0, 0, -1)));
  EXPECT_NEAR(p.distance(), 2.0, 1e-15);
  const Plane q(Eigen::Vector3d(1, 0, 0), -3.0);  // x = -3
  EXPECT_TRUE(q.normal().isApprox(Eigen::Vector3d(-1, 0, 0)));
  EXPECT_NEAR(q.distance(), 3.0, 1e-15);
  EXPECT_NEAR(q.signedDistance(Eigen::Vector3d(-3, 5, 7)), 0.0, 1e-15);
}

TEST(Plane, RejectsZeroNormal) {
  EXPECT_THROW(Plane(Eigen::Vector3d::Zero(), 1.0), Error);
  EXPECT_THROW(Plane(Eigen::Vector3d(0, 0, 1), NAN), Error);
}

TEST(Plane, TransformKeepsPointsOnPlane) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Plane plane_a(Eigen::Vector3d(n(rng), n(rng), n(rng)), 5.0 * n(rng));
    const Pose T_b_a(Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)),
                     Eigen::Vector3d(n(rng), n(rng), n(rng)) * 20.0);
    const Plane plane_b = plane_a.transformed(T_b_a);
    EXPECT_NEAR(plane_b.normal().norm(), 1.0, 1e-12);
    EXPECT_GE(plane_b.distance(), 0.0);
    // Any point on plane_a, moved to frame b, lies on plane_b.
    const Eigen::Vector3d u = plane_a.normal().unitOrthogonal();
    const Eigen::Vector3d v = plane_a.normal().cross(u);
    const Eigen::Vector3d x_a = plane_a.normal() * plane_a.distance() + 3.0 * n(rng) * u + 3.0 * n(rng) * v;
    EXPECT_NEAR(plane_b.signedDistance(T_b_a * x_a), 0.0, 1e-9);
  }
}

TEST(Plane, TransformRoundTrip) {
  std::mt19937 rng(8);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Plane plane_a(Eigen::Vector3d(n(rng), n(rng), n(rng)), 5.0 * std::abs(n(rng)) + 0.1);
    const Pose T_b_a(Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)),
                     Eigen::Vector3d(n(rng), n(rng), n(rng)) * 20.0);
    const Plane back = plane_a.transformed(T_b_a).transformed(T_b_a.inverse());
    EXPECT_TRUE(back.normal().isApprox(plane_a.normal(), 1e-10));
    EXPECT_NEAR(back.distance(), plane_a.distance(), 1e-9);
  }
}

TEST(Plane, TransformMatchesHandComputedCase) {
  // Floor z = 0 in frame a; frame b sits 1.5 m above it (x_b = x_a - (0,0,1.5)).
  const Plane floor_a(Eigen::Vector3d::UnitZ(), 0.0);
  const Pose T_b_a(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, -1.5));
  const Plane floor_b = floor_a.transformed(T_b_a);
  // In b the floor is z = -1.5, i.e. -z = 1.5.
  EXPECT_TRUE(floor_b.normal().isApprox(-Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(floor_b.distance(), 1.5, 1e-15);
}

TEST(Plane, AngleTo) {
  const Plane a(Eigen::Vector3d::UnitX(), 1.0);
  const Plane b(Eigen::Vector3d(1, 1, 0), 1.0);
  EXPECT_NEAR(a.angleTo(b), M_PI / 4, 1e-12);
}

}  // namespace
}  // namespace storey
