#include "sim/building_spec.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "common/error.h"
#include "sim/world.h"

namespace storey::sim {
namespace {

TEST(SimSpec, PresetsAreEmbedded) {
  const std::vector<std::string> names = presetNames();
  for (const char* expected : {"tiny", "default", "building-a", "building-b"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  for (const std::string& name : names) {
    const BuildingSpec spec = loadBuildingSpec(name);
    EXPECT_EQ(spec.name, name);
  }
}

TEST(SimSpec, WrittenSpecReadsBackAsTheSameSpec) {
  for (const std::string& name : presetNames()) {
    const BuildingSpec spec = loadBuildingSpec(name);
    const std::string text = buildingSpecYaml(spec);
    const BuildingSpec read = parseBuildingSpec(text, "written " + name);
    // A fixed point: the text of what was read is the text that was written.
    EXPECT_EQ(buildingSpecYaml(read), text) << name;
    EXPECT_EQ(read.building.storey_heights, spec.building.storey_heights) << name;
    EXPECT_EQ(read.seed, spec.seed);
    EXPECT_TRUE(read.sensors.T_body_lidar.isApprox(spec.sensors.T_body_lidar, 1e-15, 1e-15));
    EXPECT_NEAR(read.robot.gait.roll, spec.robot.gait.roll, 1e-15);
    EXPECT_EQ(read.sensors.imu.gyro_bias, spec.sensors.imu.gyro_bias);
  }
  // A list of any length.
  BuildingSpec seven = loadBuildingSpec("tiny");
  seven.building.storey_heights = {4.5, 3.0, 3.1, 3.2, 3.3, 3.4, 2.9};
  EXPECT_EQ(parseBuildingSpec(buildingSpecYaml(seven), "seven").building.storey_heights,
            seven.building.storey_heights);
}

TEST(SimSpec, UnknownKeyNamesKeyAndSource) {
  try {
    parseBuildingSpec("building:\n  corridor_lenght: 10\n", "my.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("my.yaml"), std::string::npos) << message;
    EXPECT_NE(message.find("building.corridor_lenght"), std::string::npos) << message;
    EXPECT_NE(message.find("line 2"), std::string::npos) << message;
  }
}

TEST(SimSpec, OutOfRangeValueNamesKey) {
  try {
    parseBuildingSpec("robot:\n  walk_speed: 5\n", "spec.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("robot.walk_speed"), std::string::npos) << e.what();
  }
}

TEST(SimSpec, UnknownPresetListsPresets) {
  try {
    loadBuildingSpec("no-such-building");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("building-a"), std::string::npos) << e.what();
  }
}

TEST(SimSpec, MountsAndStoreysAreRead) {
  const BuildingSpec spec = parseBuildingSpec(
      "building:\n  storey_heights: [3.0, 2.8]\n"
      "sensors:\n  T_body_imu:\n    translation: [0.1, 0.0, 0.0]\n"
      "    rotation_rpy_deg: [180.0, 0.0, 90.0]\n  imu:\n    rate_hz: 200\n",
      "test");
  ASSERT_EQ(spec.building.storey_heights.size(), 2u);
  EXPECT_DOUBLE_EQ(spec.building.storey_heights[1], 2.8);
  EXPECT_DOUBLE_EQ(spec.sensors.imu.rate, 200.0);
  const Eigen::Matrix3d R = spec.sensors.T_body_imu.rotationMatrix();
  // yaw 90 after roll 180: x_imu -> y_body, z_imu -> -z_body.
  EXPECT_TRUE(R.col(0).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_TRUE(R.col(2).isApprox(-Eigen::Vector3d::UnitZ(), 1e-12));
}

/// Every preset: the walk has the advertised size and returns to its start.
TEST(SimSpec, PresetWalksHaveTheAdvertisedSize) {
  struct Expect {
    const char* name;
    int storeys;
    double min_length, max_length, min_duration, max_duration;
  };
  for (const Expect& e :
       {Expect{"tiny", 1, 8, 16, 15, 28}, Expect{"default", 3, 100, 250, 120, 420},
        Expect{"building-a", 5, 350, 460, 450, 1100},
        Expect{"building-b", 6, 540, 680, 700, 1500}}) {
    const World world = makeWorld(loadBuildingSpec(e.name));
    EXPECT_EQ(static_cast<int>(world.building.storeys.size()), e.storeys) << e.name;
    EXPECT_GE(world.trajectory.pathLength(), e.min_length) << e.name;
    EXPECT_LE(world.trajectory.pathLength(), e.max_length) << e.name;
    EXPECT_GE(world.trajectory.duration(), e.min_duration) << e.name;
    EXPECT_LE(world.trajectory.duration(), e.max_duration) << e.name;
    // Reaches the top storey.
    double top = -1e9;
    for (double t = 0; t < world.trajectory.duration(); t += 0.5)
      top = std::max(top, world.trajectory.T_world_body(t).translation().z());
    EXPECT_GT(top, world.building.storeys.back().floor_z + 0.3) << e.name;
  }
}

}  // namespace
}  // namespace storey::sim
