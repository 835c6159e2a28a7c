#include "imu/so3.h"

#include <gtest/gtest.h>

#include <random>

namespace storey {
namespace {

Eigen::Vector3d randomVector(std::mt19937& rng, double scale) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Vector3d(n(rng), n(rng), n(rng)) * scale;
}

TEST(ImuSo3, ExpMatchesAngleAxisAndLogInvertsIt) {
  std::mt19937 rng(3);
  for (double scale : {1e-12, 1e-7, 1e-3, 1e-2, 0.3, 1.5}) {
    for (int i = 0; i < 50; ++i) {
      const Eigen::Vector3d phi = randomVector(rng, scale);
      if (phi.norm() >= M_PI) continue;
      const Eigen::Matrix3d expected =
          phi.norm() > 0 ? Eigen::AngleAxisd(phi.norm(), phi.normalized()).toRotationMatrix()
                         : Eigen::Matrix3d::Identity();
      EXPECT_LT((so3::expMatrix(phi) - expected).norm(), 1e-15 + 1e-14 * phi.norm());
      EXPECT_LT((so3::logQuaternion(so3::expQuaternion(phi)) - phi).norm(),
                1e-15 + 1e-13 * phi.norm());
      // -q is the same rotation.
      Eigen::Quaterniond neg = so3::expQuaternion(phi);
      neg.coeffs() *= -1.0;
      EXPECT_LT((so3::logQuaternion(neg) - phi).norm(), 1e-15 + 1e-13 * phi.norm());
    }
  }
}

TEST(ImuSo3, RightJacobianMatchesFiniteDifferencesAndInverse) {
  std::mt19937 rng(4);
  const double h = 1e-7;
  for (double scale : {1e-9, 5e-3, 2e-2, 0.5, 2.0}) {
    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector3d phi = randomVector(rng, scale);
      if (phi.norm() >= 3.0) continue;
      const Eigen::Matrix3d Jr = so3::rightJacobian(phi);
      // Exp(phi + d) = Exp(phi) Exp(Jr d): column c = Log(Exp(phi)^T Exp(phi + h e_c)) / h.
      Eigen::Matrix3d numeric;
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d d = Eigen::Vector3d::Unit(c) * h;
        numeric.col(c) =
            (so3::logQuaternion(so3::expQuaternion(phi).conjugate() * so3::expQuaternion(phi + d)) -
             so3::logQuaternion(so3::expQuaternion(phi).conjugate() *
                                so3::expQuaternion(phi - d))) /
            (2.0 * h);
      }
      EXPECT_LT((Jr - numeric).norm(), 1e-7) << "phi " << phi.transpose();
      EXPECT_LT((so3::rightJacobianInverse(phi) * Jr - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    }
  }
}

TEST(ImuSo3, SeriesAndClosedFormsAgreeAtTheSwitch) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  const Eigen::Vector3d below = axis * (so3::kSmallAngle * (1 - 1e-13));
  const Eigen::Vector3d above = axis * (so3::kSmallAngle * (1 + 1e-13));
  EXPECT_LT((so3::rightJacobian(below) - so3::rightJacobian(above)).norm(), 1e-12);
  EXPECT_LT((so3::rightJacobianInverse(below) - so3::rightJacobianInverse(above)).norm(), 1e-12);
  EXPECT_LT((so3::expMatrix(below) - so3::expMatrix(above)).norm(), 1e-10);
}

}  // namespace
}  // namespace storey
