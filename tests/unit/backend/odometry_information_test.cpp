// core/backend/odometry_information: an odometry edge's sigmas grow with the
// distance moved, the angle turned and the height climbed.
#include "backend/odometry_information.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace storey::backend {
namespace {

GraphConfig motionAware() {
  GraphConfig g;
  g.odometry_sigma_translation = 0.001;
  g.odometry_sigma_translation_per_m = 0.002;
  g.odometry_sigma_translation_per_rad = 0.004;
  g.odometry_sigma_translation_per_m_climbed = 0.01;
  g.odometry_sigma_rotation = 0.0001;
  g.odometry_sigma_rotation_per_m = 0.0002;
  g.odometry_sigma_rotation_per_rad = 0.0003;
  g.odometry_sigma_rotation_per_m_climbed = 0.001;
  return g;
}

/// A pose at `t` with yaw `yaw` and a pitch `pitch` on top (the odometry's frame is
/// gravity-aligned).
Pose at(const Eigen::Vector3d& t, double yaw, double pitch = 0.0) {
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) *
      Eigen::Quaterniond(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
  return Pose(q, t);
}

TEST(OdometryInformation, StraightLevelEdgeGrowsWithDistanceOnly) {
  const GraphConfig g = motionAware();
  // Heading north-east at 0.7 rad: the edge's own frame, not the world's, carries it.
  const OdometryEdgeSigma s = odometryEdgeSigma(
      g, at({1, 2, 3}, 0.7), at({1 + 2 * std::cos(0.7), 2 + 2 * std::sin(0.7), 3}, 0.7));
  EXPECT_NEAR(s.translation, 0.001 + 0.002 * 2.0, 1e-12);
  EXPECT_NEAR(s.rotation, 0.0001 + 0.0002 * 2.0, 1e-12);
}

TEST(OdometryInformation, TurnsAndClimbsAreLessCertain) {
  const GraphConfig g = motionAware();
  // A half-landing: a 180 deg turn on the spot.
  const OdometryEdgeSigma turn = odometryEdgeSigma(g, at({0, 0, 0}, 0.0), at({0, 0, 0}, M_PI));
  EXPECT_NEAR(turn.translation, 0.001 + 0.004 * M_PI, 1e-9);
  EXPECT_NEAR(turn.rotation, 0.0001 + 0.0003 * M_PI, 1e-9);
  // Half a metre up a flight (0.8 m along it), level sensor: the height counts, not the pitch.
  const OdometryEdgeSigma climb =
      odometryEdgeSigma(g, at({0, 0, 0}, 0.3), at({0.6245, 0, 0.5}, 0.3));
  const double distance = std::hypot(0.6245, 0.5);
  EXPECT_NEAR(climb.translation, 0.001 + 0.002 * distance + 0.01 * 0.5, 1e-9);
  EXPECT_NEAR(climb.rotation, 0.0001 + 0.0002 * distance + 0.001 * 0.5, 1e-9);
  // Going down counts the same.
  const OdometryEdgeSigma down =
      odometryEdgeSigma(g, at({0.6245, 0, 0.5}, 0.3), at({0, 0, 0}, 0.3));
  EXPECT_NEAR(down.translation, climb.translation, 1e-12);
}

TEST(OdometryInformation, PitchingTheSensorIsNotClimbing) {
  // The height change is measured in the gravity-aligned odometry frame:
  // a sensor pitched 30 deg that moves horizontally climbs nothing.
  GraphConfig g = motionAware();
  g.odometry_sigma_translation_per_rad = 0.0;
  const OdometryEdgeSigma s =
      odometryEdgeSigma(g, at({0, 0, 1}, 0.0, 0.5), at({1, 0, 1}, 0.0, 0.5));
  EXPECT_NEAR(s.translation, 0.001 + 0.002 * 1.0, 1e-12);
}

TEST(OdometryInformation, InformationIsTheInverseVariancePerAxis) {
  const GraphConfig g = motionAware();
  const Pose a = at({0, 0, 0}, 0.0), b = at({1, 0, 0.2}, 0.5);
  const OdometryEdgeSigma s = odometryEdgeSigma(g, a, b);
  const Eigen::Matrix<double, 6, 6> info = odometryEdgeInformation(g, a, b);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(info(i, i) * s.translation * s.translation, 1.0, 1e-12);
    EXPECT_NEAR(info(3 + i, 3 + i) * s.rotation * s.rotation, 1.0, 1e-12);
  }
  EXPECT_EQ((info - Eigen::Matrix<double, 6, 6>(info.diagonal().asDiagonal())).norm(), 0.0);
}

TEST(OdometryInformation, WithoutMotionTermsTheSigmaGrowsWithDistanceOnly) {
  // The model before the motion terms existed (and what a user gets with them at 0).
  GraphConfig g = motionAware();
  g.odometry_sigma_translation_per_rad = g.odometry_sigma_translation_per_m_climbed = 0.0;
  g.odometry_sigma_rotation_per_rad = g.odometry_sigma_rotation_per_m_climbed = 0.0;
  const OdometryEdgeSigma s = odometryEdgeSigma(g, at({0, 0, 0}, 0.0), at({0, 1, 0.5}, 2.0));
  const double distance = std::hypot(1.0, 0.5);
  EXPECT_EQ(s.translation,
            g.odometry_sigma_translation + g.odometry_sigma_translation_per_m * distance);
  EXPECT_EQ(s.rotation, g.odometry_sigma_rotation + g.odometry_sigma_rotation_per_m * distance);
}

TEST(OdometryInformation, DefaultsTrustStraightLevelWalkingMost) {
  // The defaults (from the odometry's measured error per edge on the
  // development seeds): a 1 m straight level edge a few mm and under 1 mrad;
  // a half-landing turn or a climbing edge several times that.
  const GraphConfig g;
  const OdometryEdgeSigma straight = odometryEdgeSigma(g, at({0, 0, 0}, 0.0), at({1, 0, 0}, 0.0));
  const OdometryEdgeSigma turn = odometryEdgeSigma(g, at({0, 0, 0}, 0.0), at({0.3, 0.3, 0}, M_PI));
  const OdometryEdgeSigma climb = odometryEdgeSigma(g, at({0, 0, 0}, 0.0), at({0.8, 0, 0.55}, 0.0));
  EXPECT_LT(straight.translation, 0.005);
  EXPECT_LT(straight.rotation, 0.001);
  EXPECT_GT(turn.translation, 3.0 * straight.translation);
  EXPECT_GT(climb.translation, 2.5 * straight.translation);
  EXPECT_GT(turn.rotation, 1.5 * straight.rotation);
  EXPECT_GT(climb.rotation, 1.5 * straight.rotation);
}

}  // namespace
}  // namespace storey::backend
