// Footprints beyond one corridor: arms (L, T, U), single-loaded corridors,
// and walks that go into rooms. The generator builds what the spec says and
// the walk goes where it should; that the walk never meets the building is
// checked over the random family in random_spec_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "sim/building.h"
#include "sim/building_spec.h"
#include "sim/raycaster.h"

namespace storey::sim {
namespace {

/// A two-storey building of a 24 m corridor, 2.2 m wide, rooms 4 m deep.
BuildingSpec twoStoreys() {
  BuildingSpec spec;
  spec.source = "test";
  spec.building.storey_heights = {3.2, 3.0};
  spec.building.corridor_length = 24.0;
  spec.building.corridor_width = 2.2;
  spec.building.room_depth = 4.0;
  spec.building.room_width = 4.0;
  spec.building.wall_thickness = 0.2;
  return spec;
}

/// Distance along `direction` from `origin` to the first returning surface (inf when none within
/// 60 m).
double castOne(const RayCaster& caster, const Eigen::Vector3d& origin,
               const Eigen::Vector3d& direction) {
  Eigen::Vector3f origins[16], directions[16];
  for (int i = 0; i < 16; ++i) {
    origins[i] = origin.cast<float>();
    directions[i] = direction.normalized().cast<float>();
  }
  RayHit hits[16];
  caster.cast16(origins, directions, 60.0f, hits);
  return hits[0].distance;
}

TEST(Footprint, AnArmIsACorridorWithRoomsAndTheWalkGoesToItsEnd) {
  BuildingSpec spec = twoStoreys();
  spec.building.arms.positions = {1.0};  // an L: flush with the east end
  spec.building.arms.lengths = {15.0};
  const Building building = generateBuilding(spec);
  const RayCaster caster(building.mesh);
  const double yc = 1.1, half = 1.1 + 4.0, x_arm = 24.0 - half, wt = 0.2;
  // Looking south down the arm's corridor from the main corridor: its glazed
  // end wall lets the ray out, so aim low, below the glass, at the wall.
  const Eigen::Vector3d in_corridor(x_arm, 0.0, 0.02);
  EXPECT_NEAR(castOne(caster, in_corridor, -Eigen::Vector3d::UnitY()), 15.0 + yc - wt / 2, 1e-3);
  // Across the arm at mid-length, above doors and windows: the walls of its
  // rooms on both sides, not further than the arm's outer walls.
  const Eigen::Vector3d mid_arm(x_arm, -yc - 9.0, 2.45);
  EXPECT_LE(castOne(caster, mid_arm, Eigen::Vector3d::UnitX()), half - wt / 2 + 1e-3);
  EXPECT_LE(castOne(caster, mid_arm, -Eigen::Vector3d::UnitX()), half - wt / 2 + 1e-3);
  // The walk goes down the arm to 1 m before its end wall, on both storeys.
  const double y_turn = -yc - (15.0 - wt / 2 - 1.0);
  int at_the_end = 0;
  for (const RouteVertex& v : building.route)
    if (std::abs(v.p.y() - y_turn) < 1e-9) ++at_the_end;
  EXPECT_EQ(at_the_end, 2 * 2);  // two corners per visit, one visit per storey
  // The south rooms of the main corridor stop at the arm: a ray along the
  // south rooms towards the east, above the furniture, meets the arm's west wall.
  const Eigen::Vector3d south_room(x_arm - half - 3.0, -yc - 2.0, 2.5);
  EXPECT_NEAR(castOne(caster, south_room, Eigen::Vector3d::UnitX()), 3.0 - wt / 2, 1e-3);
}

TEST(Footprint, AUHasTwoArmsAndATOneInTheMiddle) {
  BuildingSpec spec = twoStoreys();
  spec.building.arms.positions = {0.0, 1.0};
  spec.building.arms.lengths = {12.0, 10.0};
  const Building u = generateBuilding(spec);
  double south_most = 0.0;
  for (const RouteVertex& v : u.route) south_most = std::min(south_most, v.p.y());
  EXPECT_NEAR(south_most, -1.1 - (12.0 - 0.1 - 1.0), 1e-9);

  spec.building.arms.positions = {0.5};
  spec.building.arms.lengths = {12.0};
  const Building t = generateBuilding(spec);
  const RayCaster caster(t.mesh);
  // The main corridor's south wall is open into the arm at its middle ...
  EXPECT_GT(castOne(caster, Eigen::Vector3d(12.0, 0.0, 0.02), -Eigen::Vector3d::UnitY()), 12.0);
  // ... and closed beside it (a door or the wall of a room at most).
  EXPECT_LT(castOne(caster, Eigen::Vector3d(12.0 - 3.5, 0.0, 2.5), -Eigen::Vector3d::UnitY()), 1.2);
}

TEST(Footprint, ArmsThatDoNotFitAreRefused) {
  BuildingSpec spec = twoStoreys();
  spec.building.arms.positions = {0.4, 0.5};  // 10.2 m wide each, 2.4 m apart
  spec.building.arms.lengths = {12.0, 12.0};
  EXPECT_THROW(generateBuilding(spec), Error);
  spec.building.arms.positions = {0.5};
  spec.building.arms.lengths = {6.0};  // the rooms' depth and a turn do not fit
  EXPECT_THROW(generateBuilding(spec), Error);
  spec.building.arms.lengths = {12.0, 12.0};  // one length per position
  EXPECT_THROW(spec.validate(), Error);
}

TEST(Footprint, ASingleLoadedCorridorHasWindowsOnItsSouthSide) {
  BuildingSpec spec = twoStoreys();
  spec.building.single_loaded = true;
  spec.building.clutter_density = 0.0;  // nothing in front of the windows
  spec.building.pillar_spacing = 0.0;
  const Building single = generateBuilding(spec);
  const RayCaster caster(single.mesh);
  // Window centres at room spacing (6 windows over 24 m), 0.9 + 0.7 m up.
  const double window_z = spec.building.window_sill + spec.building.window_height / 2;
  EXPECT_TRUE(
      std::isinf(castOne(caster, Eigen::Vector3d(2.0, 0.0, window_z), -Eigen::Vector3d::UnitY())));
  // Between windows the outer wall, at the corridor's wall line.
  EXPECT_NEAR(castOne(caster, Eigen::Vector3d(4.0, 0.0, window_z), -Eigen::Vector3d::UnitY()),
              1.1 - 0.1, 1e-3);
  spec.building.atrium.rooms = 1;  // an atrium replaces south rooms: there are none
  EXPECT_THROW(spec.validate(), Error);
}

TEST(Footprint, TheWalkGoesIntoRoomsOnEveryStorey) {
  BuildingSpec spec = twoStoreys();
  spec.robot.rooms_entered = 2;
  spec.building.stairwell.floor_landing_depth = 2.0;  // the stairs' corners elsewhere in y
  const Building building = generateBuilding(spec);
  // The loop inside a room runs 0.6 + 0.9 m past the corridor wall's face.
  const double y_loop = 1.1 + 0.1 + 1.5;
  int loop_corners = 0;
  for (const RouteVertex& v : building.route)
    if (std::abs(std::abs(v.p.y()) - y_loop) < 1e-9) ++loop_corners;
  EXPECT_EQ(loop_corners, 2 * 2 * 2);  // two corners a room, two rooms a storey, two storeys
  spec.robot.rooms_entered = 0;
  const Building plain = generateBuilding(spec);
  EXPECT_LT(plain.route.size(), building.route.size());
}

}  // namespace
}  // namespace storey::sim

namespace storey::sim {
namespace {

TEST(Stairs, StraightFlightsAlternateAlongTheCorridorOneAStorey) {
  BuildingSpec spec = twoStoreys();
  spec.building.storey_heights = {3.2, 3.0, 3.4};
  spec.building.corridor_length = 30.0;
  spec.building.stairwell.kind = StairKind::kStraight;
  spec.building.stairwell.position = 0.6;
  const Building building = generateBuilding(spec);
  // The climbs: route segments that rise a whole storey, along x only, the
  // first east (lane A), the second west (lane B); the descents reverse them.
  std::vector<double> climbs;  // signed x run of each rising segment
  for (std::size_t i = 1; i < building.route.size(); ++i) {
    const Eigen::Vector3d d = building.route[i].p - building.route[i - 1].p;
    if (std::abs(d.z()) < 1.0) continue;
    EXPECT_NEAR(d.y(), 0.0, 1e-9);
    climbs.push_back(d.z() > 0 ? d.x() : -d.x());
  }
  ASSERT_EQ(climbs.size(), 4u);  // up two flights, down two
  EXPECT_GT(climbs[0], 0.0);     // east
  EXPECT_LT(climbs[1], 0.0);     // west
  EXPECT_LT(climbs[2], 0.0);     // down the second: reversed
  EXPECT_GT(climbs[3], 0.0);
  // Each flight rises as its steps: the storey height over its run, at the
  // riser and tread the spec gives (to the nearest whole riser).
  const double slope = std::abs(3.2 / climbs[0]);
  EXPECT_NEAR(slope, 0.17 / 0.28, 0.03);

  // The floor above a flight is open over it: looking down from 1 m above
  // the first floor at the flight's middle, the first hit is a step below it.
  const RayCaster caster(building.mesh);
  double x_mid = 0.0, y_lane = 0.0;
  for (std::size_t i = 1; i < building.route.size(); ++i) {
    const Eigen::Vector3d d = building.route[i].p - building.route[i - 1].p;
    if (d.z() > 1.0) {
      x_mid = (building.route[i].p.x() + building.route[i - 1].p.x()) / 2;
      y_lane = building.route[i].p.y();
      break;
    }
  }
  const double down =
      castOne(caster, Eigen::Vector3d(x_mid, y_lane, 3.2 + 1.0), -Eigen::Vector3d::UnitZ());
  EXPECT_GT(down, 1.0 + 0.5);
  EXPECT_LT(down, 1.0 + 3.2);
  // The corridor wall along the flights is glazed: from the corridor the
  // LiDAR sees the steps or the wall between the lanes, not the corridor wall.
  const double across = castOne(caster, Eigen::Vector3d(x_mid, 0.0, 1.6), Eigen::Vector3d::UnitY());
  EXPECT_GT(across, 1.1 + 0.1);
}

}  // namespace
}  // namespace storey::sim

namespace storey::sim {
namespace {

TEST(Stairs, LShapedFlightsTurnAtAQuarterLandingAndTheWalkwayLeadsBack) {
  BuildingSpec spec = twoStoreys();
  spec.building.storey_heights = {3.2, 3.0, 3.4};
  spec.building.stairwell.kind = StairKind::kLShaped;
  const Building building = generateBuilding(spec);
  // Per flight climbed: one rise along +y (flight 1), one along -x (flight 2).
  int north = 0, west = 0, other = 0;
  for (std::size_t i = 1; i < building.route.size(); ++i) {
    const Eigen::Vector3d d = building.route[i].p - building.route[i - 1].p;
    if (d.z() < 0.5) continue;
    if (d.y() > 0.5 && std::abs(d.x()) < 1e-9)
      ++north;
    else if (d.x() < -0.5 && std::abs(d.y()) < 1e-9)
      ++west;
    else
      ++other;
  }
  EXPECT_EQ(north, 2);
  EXPECT_EQ(west, 2);
  EXPECT_EQ(other, 0);
  // The well is open: from the first floor's walkway level, looking down
  // through the well beside flight 1 reaches the ground floor.
  double x_col = 0.0;
  for (std::size_t i = 1; i < building.route.size(); ++i) {
    const Eigen::Vector3d d = building.route[i].p - building.route[i - 1].p;
    if (d.z() > 0.5 && d.y() > 0.5) {
      x_col = building.route[i].p.x();
      break;
    }
  }
  const RayCaster caster(building.mesh);
  const double lane = (spec.building.stairwell.width - 0.1) / 2;
  const double y_well = 1.1 + spec.building.stairwell.floor_landing_depth + 0.3;
  EXPECT_NEAR(
      castOne(caster, Eigen::Vector3d(x_col - lane, y_well, 3.2 + 1.0), -Eigen::Vector3d::UnitZ()),
      3.2 + 1.0, 1e-3);
}

}  // namespace
}  // namespace storey::sim

namespace storey::sim {
namespace {

TEST(Footprint, ASplitLevelArmIsReachedUpARamp) {
  BuildingSpec spec = twoStoreys();
  spec.building.arms.positions = {0.5};
  spec.building.arms.lengths = {16.0};
  spec.building.arms.rises = {0.5};  // a 6 m ramp at 1:12
  const Building building = generateBuilding(spec);
  const RayCaster caster(building.mesh);
  const double yc = 1.1, x_arm = 12.0;
  auto floorBelow = [&](double y, double z_from) {
    return z_from - castOne(caster, Eigen::Vector3d(x_arm, y, z_from), -Eigen::Vector3d::UnitZ());
  };
  // The corridor floor: the main level at the junction, half way up the ramp
  // at 3 m, the arm's level beyond 6 m; on both storeys.
  for (double level : {0.0, 3.2}) {
    EXPECT_NEAR(floorBelow(-yc - 0.05, level + 1.5), level, 0.01);
    EXPECT_NEAR(floorBelow(-yc - 3.0, level + 1.5), level + 0.25, 0.01);
    EXPECT_NEAR(floorBelow(-yc - 10.0, level + 1.5), level + 0.5, 1e-6);
  }
  // The walk goes up the ramp and down again on every storey: the body is
  // 0.5 m higher at the arm's end than in the main corridor.
  const double body = spec.robot.body_height;
  int at_arm_level = 0;
  for (const RouteVertex& v : building.route)
    if (v.p.y() < -yc - 6.0 - 1e-9) {
      EXPECT_TRUE(std::abs(v.p.z() - (body + 0.5)) < 1e-9 ||
                  std::abs(v.p.z() - (3.2 + body + 0.5)) < 1e-9)
          << v.p.transpose();
      ++at_arm_level;
    }
  EXPECT_EQ(at_arm_level, 2 * 2);
  spec.building.arms.lengths = {8.0};  // too short for its ramp and a turn
  EXPECT_THROW(generateBuilding(spec), Error);
}

}  // namespace
}  // namespace storey::sim
