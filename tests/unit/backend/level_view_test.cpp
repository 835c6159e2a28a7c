#include "backend/level_view.h"

#include <gtest/gtest.h>

#include <cmath>

namespace storey::backend {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Vector3d tiltedUp(double angle_rad, double azimuth_rad, double sign = 1.0) {
  return sign * Eigen::Vector3d(std::sin(angle_rad) * std::cos(azimuth_rad),
                                std::sin(angle_rad) * std::sin(azimuth_rad), std::cos(angle_rad));
}

TEST(LevelView, AViewOfAFloorTiltedBeyondTheGateIsTilted) {
  const Eigen::Vector3d floor(0, 0, -1);  // a floor's landmark, seen from above
  for (double azimuth : {0.0, 1.0, 2.5, -2.0}) {
    EXPECT_TRUE(isTiltedLevelView(floor, tiltedUp(0.010, azimuth, -1.0), 5 * kDeg, 0.0075));
    EXPECT_FALSE(isTiltedLevelView(floor, tiltedUp(0.005, azimuth, -1.0), 5 * kDeg, 0.0075));
    // The view's orientation does not matter (a normal up or down).
    EXPECT_TRUE(isTiltedLevelView(floor, tiltedUp(0.010, azimuth), 5 * kDeg, 0.0075));
  }
}

TEST(LevelView, CeilingsCountAsLevelSurfaces) {
  const Eigen::Vector3d ceiling(0.001, 0, 1);  // seen from below
  EXPECT_TRUE(isTiltedLevelView(ceiling, tiltedUp(0.016, 0.3), 5 * kDeg, 0.0075));
  EXPECT_FALSE(isTiltedLevelView(ceiling, tiltedUp(0.002, 0.3), 5 * kDeg, 0.0075));
}

TEST(LevelView, WallsAndRampsAreNotLevelSurfaces) {
  const Eigen::Vector3d wall(0.966, -0.259, 0.0);
  EXPECT_FALSE(isTiltedLevelView(wall, wall, 5 * kDeg, 0.0075));
  // A 1:12 ramp (4.8 deg) is level for a 5 deg tolerance, not for 1 deg.
  const Eigen::Vector3d ramp = tiltedUp(4.8 * kDeg, 0.0);
  EXPECT_TRUE(isTiltedLevelView(ramp, ramp, 5 * kDeg, 0.0075));
  EXPECT_FALSE(isTiltedLevelView(ramp, ramp, 1 * kDeg, 0.0075));
}

TEST(LevelView, ZeroTurnsTheTestOff) {
  EXPECT_FALSE(isTiltedLevelView(Eigen::Vector3d::UnitZ(), tiltedUp(0.2, 0.0), 5 * kDeg, 0.0));
}

}  // namespace
}  // namespace storey::backend
