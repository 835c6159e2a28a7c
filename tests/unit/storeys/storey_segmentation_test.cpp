// Storey segmentation on a synthetic three-storey building with known floor
// elevations (not evenly spaced), ceilings, walls, a table and a straight
// stair flight between each pair of floors; footprints of known rectangles.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/error.h"
#include "storeys/storey_segmentation.h"

namespace storey {
namespace {

constexpr double kLength = 14.0, kWidth = 8.0;  // building footprint [m]
// Stairwell (a hole in the floors above the lowest): x in [8.5, 13.5], y in [6.5, 8].
constexpr double kStairX0 = 8.5, kStairX1 = 13.5, kStairY0 = 6.5;
constexpr double kSlab = 0.25, kSpacing = 0.04, kNoise = 0.01, kSensorHeight = 0.6;
constexpr double kWingRise = 0.45, kWingLength = 18.0;  // split-level wing east of x = kLength

bool inStairwell(double x, double y) {
  return x >= kStairX0 && x <= kStairX1 && y >= kStairY0;
}

struct Building {
  std::vector<double> floors{0.0, 3.1, 6.4};
  MapCloud map;
  std::vector<Eigen::Vector3d> keyframes;
  std::vector<bool> truly_stairs;      ///< points of the stair flights (treads and risers)
  std::vector<std::size_t> seen_from;  ///< storey whose keyframes see the point
  std::vector<int> seen_side;  ///< +1: seen from above (floors), -1: from below (ceilings), 0: any
  std::vector<std::size_t> keyframe_storey;
  std::size_t current = 0;
  std::mt19937 rng{42};

  void add(const Eigen::Vector3d& p, bool stairs = false, int side = 0) {
    std::normal_distribution<double> noise(0.0, kNoise);
    map.positions.emplace_back(
        (p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng))).cast<float>());
    map.intensity.push_back(50.0f);
    map.time.push_back(0.0);
    map.keyframe.push_back(-1);
    map.storey.push_back(kNoStorey);
    map.flags.push_back(0);
    truly_stairs.push_back(stairs);
    seen_from.push_back(current);
    seen_side.push_back(side);
  }
  void horizontal(double z, double x0, double x1, double y0, double y1, bool hole, int side) {
    for (double x = x0; x <= x1; x += kSpacing)
      for (double y = y0; y <= y1; y += kSpacing)
        if (!(hole && inStairwell(x, y))) add({x, y, z}, false, side);
  }
  void wallX(double x, double z0, double z1) {
    for (double y = 0; y <= kWidth; y += kSpacing)
      for (double z = z0; z <= z1; z += kSpacing) add({x, y, z});
  }
  void wallY(double y, double z0, double z1) {
    for (double x = 0; x <= kLength; x += kSpacing)
      for (double z = z0; z <= z1; z += kSpacing) add({x, y, z});
  }

  /// `wing`: a split level east of the building on every storey, kWingRise
  /// above the main floor and larger than it, walked before the corridor.
  /// `sensor`: the sensor's height above the floor it stands on.
  explicit Building(bool wing = false, double sensor = kSensorHeight) {
    for (std::size_t k = 0; k < floors.size(); ++k) {
      current = k;
      const double f = floors[k];
      const double next = k + 1 < floors.size() ? floors[k + 1] : f + 3.0;
      const double ceiling = next - kSlab;
      if (wing) {
        horizontal(f + kWingRise, kLength, kLength + kWingLength, 0, kWidth, false, +1);
        for (double x = kLength + 1.0; x <= kLength + kWingLength; x += 1.0) {
          keyframes.push_back({x, 4.0, f + kWingRise + sensor});
          keyframe_storey.push_back(k);
        }
      }
      horizontal(f, 0, kLength, 0, kWidth, k > 0, +1);
      horizontal(ceiling, 0, kLength, 0, kWidth, k + 1 < floors.size(), -1);
      wallX(0, f, ceiling);
      wallX(kLength, f, ceiling);
      wallY(0, f, ceiling);
      wallY(kWidth, f, ceiling);
      horizontal(f + 0.45, 2.0, 3.6, 1.0, 1.8, false,
                 +1);  // a low table (1.3 m^2), seen from above
      // Walk along the corridor, then (below the top) up the stairs.
      for (double x = 1.0; x <= 8.0; x += 1.0) {
        keyframes.push_back({x, 7.2, f + sensor});
        keyframe_storey.push_back(k);
      }
      if (k + 1 < floors.size()) {
        const int steps = static_cast<int>(std::round((next - f) / 0.17));
        const double riser = (next - f) / steps, tread = (kStairX1 - kStairX0) / steps;
        for (int s = 0; s < steps; ++s) {
          const double x0 = kStairX0 + s * tread, z = f + (s + 1) * riser;
          for (double x = x0; x <= x0 + tread; x += kSpacing)  // tread
            for (double y = kStairY0; y <= kWidth; y += kSpacing) add({x, y, z}, true, +1);
          for (double zz = z - riser; zz <= z; zz += kSpacing)  // riser
            for (double y = kStairY0; y <= kWidth; y += kSpacing) add({x0, y, zz}, true);
          if (s % 3 == 0 || s + 1 == steps) {  // the last on the top tread
            keyframes.push_back({x0, 7.2, z + sensor});
            keyframe_storey.push_back(k);
          }
        }
        // Off the flight onto the landing of the floor above.
        keyframes.push_back({kStairX1 + 0.3, 7.2, next + sensor});
        keyframe_storey.push_back(k + 1);
      }
    }
    // Each point is observed by the nearest keyframe of its storey (slabs occlude).
    for (std::size_t i = 0; i < map.size(); ++i) {
      double best = 1e9;
      for (std::size_t k = 0; k < keyframes.size(); ++k) {
        if (keyframe_storey[k] != seen_from[i]) continue;
        const double dz = keyframes[k].z() - map.positions[i].z();
        if (dz * seen_side[i] < 0.0) continue;  // the sensor sees the surface's front
        const double d = (keyframes[k] - map.positions[i].cast<double>()).squaredNorm();
        if (d < best) {
          best = d;
          map.keyframe[i] = static_cast<std::int32_t>(k);
        }
      }
    }
  }
};

TEST(StoreySegmentation, ThreeStoreysWithStairs) {
  Building b;
  // Fixture checks: the stairs are there, the table is large enough to be a
  // region but far smaller than a floor.
  ASSERT_GT(std::count(b.truly_stairs.begin(), b.truly_stairs.end(), true), 5000);
  const StoreysConfig config;
  ASSERT_GT(1.6 * 0.8, config.min_region_area);

  const StoreySegmentation result = segmentStoreys(b.map, b.keyframes, config);
  ASSERT_EQ(result.storeys.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const StoreyInfo& s = result.storeys[k];
    EXPECT_EQ(s.index, static_cast<int>(k));
    EXPECT_NEAR(s.floor_elevation, b.floors[k], 0.05) << "storey " << k;
    ASSERT_TRUE(s.ceiling_elevation.has_value()) << "storey " << k;
    const double next = k + 1 < 3 ? b.floors[k + 1] : b.floors[k] + 3.0;
    EXPECT_NEAR(*s.ceiling_elevation, next - kSlab, 0.05);
    EXPECT_NEAR(*s.clear_height, next - kSlab - b.floors[k], 0.07);
    if (k < 2) {
      EXPECT_NEAR(*s.height, b.floors[k + 1] - b.floors[k], 0.07);
    }
    // Footprint: the floor rectangle (the lowest one whole, the others minus
    // the stairwell hole, which the alpha shape may close in part).
    const double full = kLength * kWidth, hole = (kStairX1 - kStairX0) * (kWidth - kStairY0);
    EXPECT_GT(s.footprint_area, (k == 0 ? full : full - hole) * 0.95) << "storey " << k;
    EXPECT_LT(s.footprint_area, full * 1.01) << "storey " << k;
    EXPECT_GE(s.footprint.size(), 4u);
  }
  EXPECT_GE(result.stats.slabs_too_close + result.stats.slabs_too_small, 1u);  // the tables

  // Labels: by elevation; stairs between two floors get the storey below.
  std::size_t stairs_true = 0, stairs_flagged = 0, others_flagged = 0, others = 0;
  for (std::size_t i = 0; i < b.map.size(); ++i) {
    const double z = b.map.positions[i].z();
    const std::size_t expected = z < b.floors[1] - 0.15 ? 0 : (z < b.floors[2] - 0.15 ? 1 : 2);
    const bool flagged = b.map.flags[i] & kMapPointStairs;
    if (b.truly_stairs[i]) {
      // The top tread is at the next floor's level and belongs to it.
      if (std::abs(z - b.floors[1]) < 0.1 || std::abs(z - b.floors[2]) < 0.1) continue;
      ++stairs_true;
      stairs_flagged += flagged;
      EXPECT_EQ(b.map.storey[i], static_cast<std::int16_t>(expected));
    } else {
      ASSERT_EQ(b.map.storey[i], static_cast<std::int16_t>(expected)) << "z " << z;
      // Walls and ceiling of the stairwell may be flagged too; nothing else.
      const double x = b.map.positions[i].x(), y = b.map.positions[i].y();
      if (x > kStairX0 - 1.0 && x < kStairX1 + 1.0 && y > kStairY0 - 1.0) continue;
      ++others;
      others_flagged += flagged;
    }
  }
  EXPECT_GT(static_cast<double>(stairs_flagged) / stairs_true, 0.95);
  EXPECT_GT(others, 400000u);
  EXPECT_EQ(others_flagged, 0u);
}

// A split level: every storey has a wing a ramp higher (0.45 m) and larger
// than the main floor. The storey's floor is the main floor, where the stair
// flights start and end; without the flights only area decides (the wing).
TEST(StoreySegmentation, SplitLevelFloorIsWhereTheStairsArrive) {
  Building b(true);
  const StoreysConfig config;
  ASSERT_GT(kWingLength * kWidth, kLength * kWidth);  // the wing is the larger level
  MapCloud without_flights = b.map;

  const StoreySegmentation result = segmentStoreys(b.map, b.keyframes, config);
  ASSERT_EQ(result.storeys.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(result.storeys[k].floor_elevation, b.floors[k], 0.05) << "storey " << k;

  // The same walk without the stair flights' keyframes (unknown poses): the
  // larger level wins.
  std::vector<Eigen::Vector3d> no_flights = b.keyframes;
  for (Eigen::Vector3d& k : no_flights)
    if (k.x() >= kStairX0 && k.x() <= kStairX1) k.setConstant(std::nan(""));
  const StoreySegmentation by_area = segmentStoreys(without_flights, no_flights, config);
  ASSERT_EQ(by_area.storeys.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(by_area.storeys[k].floor_elevation, b.floors[k] + kWingRise, 0.05)
        << "storey " << k;
}

// The same split level walked with the sensor carried 1.2 m above the floor
// (hand-held): at the top of each flight the wing next to the landing is
// 0.75 m below the sensor, as a floor would be under a legged robot. The
// flight still arrives at the main floor, one usual sensor height below.
TEST(StoreySegmentation, SplitLevelFloorWithTheSensorHigherThanTheWingsRise) {
  constexpr double kHandHeld = 1.2;
  ASSERT_GT(kHandHeld - kWingRise, 0.5);  // the wing would pass for a floor under the sensor
  Building b(true, kHandHeld);
  const StoreySegmentation result = segmentStoreys(b.map, b.keyframes, StoreysConfig{});
  ASSERT_EQ(result.storeys.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(result.storeys[k].floor_elevation, b.floors[k], 0.05) << "storey " << k;
  EXPECT_NEAR(result.stats.usual_sensor_height, kHandHeld, 0.03);
  EXPECT_EQ(result.stats.flight_ends, 4u);  // two flights
  EXPECT_EQ(result.stats.flight_ends_on_floor, 4u);
}

TEST(StoreySegmentation, NoFloorGivesNoStoreys) {
  MapCloud map;
  for (int i = 0; i < 2000; ++i) {  // a single wall
    map.positions.emplace_back(0.0f, 0.01f * (i % 100), 0.05f * (i / 100));
    map.intensity.push_back(1);
    map.time.push_back(0);
    map.keyframe.push_back(0);
    map.storey.push_back(3);
    map.flags.push_back(0);
  }
  const StoreySegmentation result = segmentStoreys(map, {Eigen::Vector3d(2, 0.5, 0.5)}, {});
  EXPECT_TRUE(result.storeys.empty());
  for (std::int16_t s : map.storey) EXPECT_EQ(s, kNoStorey);
}

TEST(StoreySegmentation, ConfigIsValidated) {
  StoreysConfig c;
  c.voxel_size = 0;
  EXPECT_THROW(c.validate(), Error);
  c = {};
  c.max_clear_height = 1.0;
  EXPECT_THROW(c.validate(), Error);
  EXPECT_NO_THROW(StoreysConfig{}.validate());
}

TEST(Footprint, AlphaShapeOfARectangleHasItsArea) {
  std::vector<Eigen::Vector2d> points;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (int i = 0; i <= 100; ++i)
    for (int j = 0; j <= 60; ++j) {
      const bool edge = i == 0 || i == 100 || j == 0 || j == 60;
      points.emplace_back(0.1 * i + (edge ? 0 : jitter(rng)), 0.1 * j + (edge ? 0 : jitter(rng)));
    }
  const Footprint f = alphaShapeFootprint(points, 1.0);
  EXPECT_NEAR(f.area, 60.0, 0.01);
  ASSERT_GE(f.polygon.size(), 4u);
  double signed_area = 0.0;
  for (std::size_t i = 0; i < f.polygon.size(); ++i) {
    const auto& p = f.polygon[i];
    const auto& q = f.polygon[(i + 1) % f.polygon.size()];
    signed_area += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  EXPECT_NEAR(signed_area, 60.0, 0.01);  // counter-clockwise, the outer boundary
  // An L shape: the alpha shape follows the notch (the convex hull would not).
  std::vector<Eigen::Vector2d> l_shape;
  for (const auto& p : points)
    if (!(p.x() > 5.05 && p.y() > 3.05)) l_shape.push_back(p);
  EXPECT_NEAR(alphaShapeFootprint(l_shape, 0.5).area, 60.0 - 4.95 * 2.95, 0.6);
}

}  // namespace
}  // namespace storey
