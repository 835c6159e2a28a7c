#include "types/pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/error.h"

namespace storey {
namespace {

Pose randomPose(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return Pose(q, Eigen::Vector3d(n(rng), n(rng), n(rng)) * 10.0);
}

TEST(Pose, ComposeMatchesMatrixProduct) {
  std::mt19937 rng(1);
  for (int i = 0; i < 100; ++i) {
    const Pose T_c_b = randomPose(rng);
    const Pose T_b_a = randomPose(rng);
    const Eigen::Matrix4d expected = T_c_b.matrix() * T_b_a.matrix();
    EXPECT_TRUE((T_c_b * T_b_a).matrix().isApprox(expected, 1e-12));
    const Eigen::Vector3d x_a(1.5, -2.0, 0.25);
    EXPECT_TRUE(((T_c_b * T_b_a) * x_a).isApprox(T_c_b * (T_b_a * x_a), 1e-12));
  }
}

TEST(Pose, InverseComposesToIdentity) {
  std::mt19937 rng(2);
  for (int i = 0; i < 100; ++i) {
    const Pose T = randomPose(rng);
    EXPECT_TRUE((T * T.inverse()).isApprox(Pose::identity(), 1e-12, 1e-12));
    EXPECT_TRUE((T.inverse() * T).isApprox(Pose::identity(), 1e-12, 1e-12));
    EXPECT_TRUE(T.inverse().matrix().isApprox(T.matrix().inverse(), 1e-10));
  }
}

TEST(Pose, Associative) {
  std::mt19937 rng(3);
  const Pose a = randomPose(rng), b = randomPose(rng), c = randomPose(rng);
  EXPECT_TRUE(((a * b) * c).isApprox(a * (b * c), 1e-12, 1e-12));
}

TEST(Pose, QuaternionIsNormalisedWithNonNegativeW) {
  const Pose T(Eigen::Quaterniond(-2.0, 0.0, 0.0, 2.0), Eigen::Vector3d::Zero());
  EXPECT_NEAR(T.rotation().norm(), 1.0, 1e-15);
  EXPECT_GE(T.rotation().w(), 0.0);
  // -q and q are the same rotation: 90 deg about z.
  EXPECT_TRUE((T * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY(), 1e-12));
  std::mt19937 rng(4);
  for (int i = 0; i < 100; ++i) {
    const Pose P = randomPose(rng) * randomPose(rng) * randomPose(rng).inverse();
    EXPECT_NEAR(P.rotation().norm(), 1.0, 1e-14);
  }
}

TEST(Pose, RejectsDegenerateQuaternion) {
  EXPECT_THROW(Pose(Eigen::Quaterniond(0, 0, 0, 0), Eigen::Vector3d::Zero()), Error);
  EXPECT_THROW(Pose(Eigen::Quaterniond(NAN, 0, 0, 1), Eigen::Vector3d::Zero()), Error);
  EXPECT_THROW(Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, INFINITY, 0)), Error);
}

TEST(Pose, AngleOfKnownRotation) {
  const Pose T(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())),
               Eigen::Vector3d::Zero());
  EXPECT_NEAR(T.angle(), 0.3, 1e-12);
  EXPECT_NEAR(T.inverse().angle(), 0.3, 1e-12);
}

TEST(Pose, IsometryRoundTrip) {
  std::mt19937 rng(5);
  const Pose T = randomPose(rng);
  EXPECT_TRUE(Pose::fromIsometry(T.isometry()).isApprox(T, 1e-12, 1e-12));
}

}  // namespace
}  // namespace storey
