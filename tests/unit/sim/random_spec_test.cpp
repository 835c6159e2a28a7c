// Random buildings (`random:SEED`): every seed of the development set draws a
// valid building that the generator accepts, seeds differ and spread over
// the drawn ranges, a seed always gives the same spec, and a simulated
// folder's spec.yaml reproduces the folder byte for byte.
#include "sim/random_spec.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "common/error.h"
#include "sim/building.h"
#include "sim/raycaster.h"
#include "sim/simulator.h"
#include "sim/world.h"
#include "support/temp_dir.h"

namespace storey::sim {
namespace {

TEST(RandomSpec, SeedsOneToThirtyAreValidDifferAndSpread) {
  std::set<std::string> texts;
  std::set<int> storeys, wings, rates, models, grades, motions, orientation;
  int pitched = 0, single_loaded = 0, rooms_entered = 0, wide_stairs = 0, straight_stairs = 0,
      l_stairs = 0, split_levels = 0;
  std::set<std::string> footprints;  // corridor, L, T, U
  double min_slope = 90, max_slope = 0, min_height = 10, max_height = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const BuildingSpec spec = loadBuildingSpec("random:" + std::to_string(seed));
    EXPECT_EQ(spec.name, "random-" + std::to_string(seed));
    EXPECT_EQ(spec.seed, seed);
    EXPECT_NO_THROW(spec.validate());
    const Building building = generateBuilding(spec);
    EXPECT_EQ(building.storeys.size(), spec.building.storey_heights.size());
    texts.insert(buildingSpecYaml(spec));
    const auto& b = spec.building;
    storeys.insert(static_cast<int>(b.storey_heights.size()));
    wings.insert(b.wings);
    rates.insert(static_cast<int>(spec.sensors.imu.rate));
    models.insert(static_cast<int>(spec.sensors.lidar.model));
    ASSERT_TRUE(spec.sensors.imu.grade.has_value());
    grades.insert(static_cast<int>(*spec.sensors.imu.grade));
    const ImuRateRange range = imuGradeRates(*spec.sensors.imu.grade);
    EXPECT_GE(spec.sensors.imu.rate, range.min_hz);
    EXPECT_LE(spec.sensors.imu.rate, range.max_hz);
    motions.insert(static_cast<int>(spec.robot.motion));
    orientation.insert(spec.sensors.imu.orientation ? 1 : 0);
    for (double h : b.storey_heights) {
      EXPECT_GE(h, 2.7);
      EXPECT_LE(h, 4.8);
      min_height = std::min(min_height, h);
      max_height = std::max(max_height, h);
    }
    EXPECT_GE(b.slab_thickness, 0.2);
    EXPECT_LE(b.slab_thickness, 0.4);
    EXPECT_GE(b.stairwell.riser, 0.15);
    EXPECT_LE(b.stairwell.riser, 0.20);
    EXPECT_GE(b.stairwell.tread, 0.25);
    EXPECT_LE(b.stairwell.tread, 0.32);
    const double slope = std::atan2(b.stairwell.riser, b.stairwell.tread) * 180.0 / M_PI;
    min_slope = std::min(min_slope, slope);
    max_slope = std::max(max_slope, slope);
    const Eigen::Vector3d lidar_up =
        spec.sensors.T_body_lidar.rotation() * Eigen::Vector3d::UnitZ();
    const double tilt = std::acos(std::clamp(lidar_up.z(), -1.0, 1.0)) * 180.0 / M_PI;
    EXPECT_LE(tilt, 25.0 + 1e-9);
    pitched += tilt > 1.0;
    EXPECT_LE(spec.sensors.T_body_imu.translation().norm(), 0.3 + 1e-3);
    single_loaded += b.single_loaded;
    rooms_entered += spec.robot.rooms_entered > 0;
    wide_stairs += b.stairwell.width >= 4.0;
    straight_stairs += b.stairwell.kind == StairKind::kStraight;
    l_stairs += b.stairwell.kind == StairKind::kLShaped;
    split_levels += !b.arms.rises.empty();
    const auto& arms = b.arms.positions;
    const bool at_end = !arms.empty() && (arms[0] == 0.0 || arms[0] == 1.0);
    footprints.insert(arms.empty() ? "corridor" : arms.size() == 2 ? "U" : at_end ? "L" : "T");
  }
  EXPECT_EQ(texts.size(), 30u) << "two seeds drew the same spec";
  EXPECT_GE(storeys.size(), 5u) << "storey counts 2-7 should almost all appear in 30 seeds";
  EXPECT_EQ(*storeys.begin() >= 2 && *storeys.rbegin() <= 7, true);
  EXPECT_EQ(wings.size(), 2u);
  EXPECT_GE(rates.size(), 3u);        // 100, 200, 400 Hz
  EXPECT_EQ(models.size(), 4u);       // VLP-16, VLP-32C, HDL-32E, OS1-64
  EXPECT_EQ(grades.size(), 2u);       // tactical, consumer
  EXPECT_EQ(motions.size(), 2u);      // legged, handheld
  EXPECT_EQ(orientation.size(), 2u);  // with and without the orientation field
  EXPECT_GT(pitched, 5);
  EXPECT_LT(pitched, 25);
  EXPECT_LT(min_slope, 30.0);
  EXPECT_GT(max_slope, 33.0);
  EXPECT_LT(min_height, 3.0);
  EXPECT_GT(max_height, 4.0);
  EXPECT_EQ(footprints.size(), 4u);
  EXPECT_GE(single_loaded, 2);
  EXPECT_GE(rooms_entered, 8);
  EXPECT_GE(wide_stairs, 2);
  EXPECT_GE(straight_stairs, 4);
  EXPECT_GE(l_stairs, 3);
  EXPECT_GE(split_levels, 1);
}

/// Closest surface within `range` of x (16 rays over the sphere), or range when none.
double clearance(const RayCaster& caster, const Eigen::Vector3d& x, float range) {
  Eigen::Vector3f origins[16], directions[16];
  for (int i = 0; i < 16; ++i) {
    // A Fibonacci sphere of 16 directions.
    const double z = 1.0 - (i + 0.5) / 8.0, r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = i * M_PI * (3.0 - std::sqrt(5.0));
    origins[i] = x.cast<float>();
    directions[i] = Eigen::Vector3f(static_cast<float>(r * std::cos(phi)),
                                    static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
  }
  RayHit hits[16];
  caster.cast16(origins, directions, range, hits);
  double closest = range;
  for (const RayHit& h : hits) closest = std::min(closest, static_cast<double>(h.distance));
  return closest;
}

TEST(RandomSpec, TheRouteNeverMeetsTheBuilding) {
  // The body centre keeps 0.2 m and the LiDAR 0.1 m from every returning
  // surface over the whole walk, in every building of the development set.
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const BuildingSpec spec = loadBuildingSpec("random:" + std::to_string(seed));
    const World world = makeWorld(spec);
    const RayCaster caster(world.building.mesh);
    for (double t = 0.0; t < world.trajectory.duration(); t += 0.1) {
      const Pose T_world_body = world.trajectory.T_world_body(t);
      const Eigen::Vector3d body = T_world_body.translation();
      const Eigen::Vector3d lidar = (T_world_body * spec.sensors.T_body_lidar).translation();
      ASSERT_GE(clearance(caster, body, 0.2f), 0.2) << "seed " << seed << ", body at t = " << t;
      ASSERT_GE(clearance(caster, lidar, 0.1f), 0.1) << "seed " << seed << ", LiDAR at t = " << t;
    }
  }
}

TEST(RandomSpec, SameSeedSameSpec) {
  EXPECT_EQ(buildingSpecYaml(drawRandomSpec(7)), buildingSpecYaml(drawRandomSpec(7)));
  EXPECT_NE(buildingSpecYaml(drawRandomSpec(7)), buildingSpecYaml(drawRandomSpec(8)));
}

TEST(RandomSpec, RigOverridesReplaceTheDrawsOnly) {
  BuildingSpec spec = drawRandomSpec(11);
  const Pose lidar_mount = spec.sensors.T_body_lidar;
  const double lane = spec.robot.lane_offset;
  const bool orientation = spec.sensors.imu.orientation;
  applyRigOverrides(spec, {"OS1-64", "consumer@100", "handheld"});
  EXPECT_EQ(spec.sensors.lidar.model, LidarModel::kOs1_64);
  EXPECT_TRUE(spec.sensors.T_body_lidar.isApprox(lidar_mount));
  EXPECT_EQ(spec.sensors.imu.grade, ImuGrade::kConsumer);
  EXPECT_EQ(spec.sensors.imu.rate, 100.0);
  EXPECT_EQ(spec.sensors.imu.orientation, orientation);
  EXPECT_EQ(spec.robot.motion, RobotMotion::kHandheld);
  EXPECT_EQ(spec.robot.lane_offset, lane);
  EXPECT_NO_THROW(spec.validate());
  applyRigOverrides(spec, {"", "tactical", "legged"});
  EXPECT_EQ(spec.sensors.imu.rate, imuGradeRates(ImuGrade::kTactical).max_hz);
  EXPECT_EQ(spec.robot.motion, RobotMotion::kLegged);
  EXPECT_THROW(applyRigOverrides(spec, {"VLP-64", "", ""}), Error);
  EXPECT_THROW(applyRigOverrides(spec, {"", "consumer@x", ""}), Error);
  EXPECT_THROW(applyRigOverrides(spec, {"", "tactical@1000", ""}), Error);
  EXPECT_THROW(applyRigOverrides(spec, {"", "", "wheeled"}), Error);
}

TEST(RandomSpec, NameParsing) {
  EXPECT_EQ(randomSeedOf("random:42"), 42u);
  EXPECT_FALSE(randomSeedOf("building-a"));
  EXPECT_THROW(randomSeedOf("random:"), Error);
  EXPECT_THROW(randomSeedOf("random:x1"), Error);
  EXPECT_THROW(randomSeedOf("random:-3"), Error);
}

TEST(RandomSpec, SpecYamlReproducesTheFolder) {
  test::TempDir dir;
  SimulationOptions options;
  options.max_duration = 3.0;
  options.threads = 2;
  const std::filesystem::path a = dir.path() / "a", b = dir.path() / "b";
  simulate(loadBuildingSpec("random:5"), options, a.string());
  simulate(loadBuildingSpec((a / kSpecFile).string()), options, b.string());
  for (const char* name : {kSpecFile, kBagFile, kLidarTruthFile, kImuTruthFile, kMeshFile,
                           kStoreysFile, kCalibrationFile}) {
    const std::string first = test::readText((a / name).string());
    EXPECT_FALSE(first.empty()) << name;
    EXPECT_TRUE(first == test::readText((b / name).string())) << name << " differs";
  }
}

TEST(RandomSpec, TheWorldFrameFollowsTheLidarsHeading) {
  // Storey's world frame: x = the LiDAR's initial heading, origin at the LiDAR.
  test::TempDir dir;
  SimulationOptions options;
  options.max_duration = 0.5;
  options.threads = 2;
  BuildingSpec spec = loadBuildingSpec("random:5");
  spec.sensors.T_body_lidar =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())),
           Eigen::Vector3d(0.2, 0.0, 0.1));
  simulate(spec, options, dir.path().string());
  std::ifstream truth(dir.path() / kLidarTruthFile);
  std::string line;
  while (std::getline(truth, line) && line[0] == '#') {
  }
  std::istringstream first(line);
  double t, x, y, z, qx, qy, qz, qw;
  first >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
  EXPECT_NEAR(Eigen::Vector3d(x, y, z).norm(), 0.0, 1e-6);
  const Eigen::Vector3d heading = Eigen::Quaterniond(qw, qx, qy, qz) * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(heading.y(), 0.0, 1e-6);
  EXPECT_GT(heading.x(), 0.0);
}

}  // namespace
}  // namespace storey::sim
