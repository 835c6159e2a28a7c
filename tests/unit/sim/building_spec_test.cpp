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

/// Every key of the sensor rigs and walks, set away from its default, is
/// written and read back.
TEST(SimSpec, SensorAndMotionKeysRoundTrip) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.robot = robotForMotion(RobotMotion::kHandheld);
  spec.robot.walk_speed = 1.15;
  spec.robot.handheld_gait.frequency = 1.7;
  spec.robot.handheld_gait.bounce = 0.025;
  spec.robot.handheld_gait.sway = 0.02;
  spec.robot.handheld_gait.roll = 0.03;
  spec.robot.handheld_gait.pitch = 0.02;
  spec.robot.handheld_gait.yaw = 0.01;
  spec.robot.handheld_gait.slope_pitch = 0.25;
  spec.sensors.lidar.model = LidarModel::kOs1_64;
  spec.sensors.lidar.rotation_rate = 20.0;
  spec.sensors.imu = imuGrade(ImuGrade::kConsumer, 150.0);
  spec.sensors.imu.orientation = true;
  spec.sensors.imu.orientation_sigma = Eigen::Vector3d(0.01, 0.02, 0.09);
  spec.sensors.T_body_lidar =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(-0.7, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY())),
           Eigen::Vector3d(0.1, 0.0, 0.2));
  spec.sensors.T_body_imu =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitX())),
           Eigen::Vector3d(0.3, -0.1, 0.05));
  const std::string text = buildingSpecYaml(spec);
  for (const char* key :
       {"motion: handheld", "handheld_gait:", "slope_pitch:", "yaw_deg:", "model: OS1-64",
        "grade: consumer", "orientation: true", "orientation_sigma_deg:"})
    EXPECT_NE(text.find(key), std::string::npos) << key << " not in\n" << text;
  const BuildingSpec read = parseBuildingSpec(text, "written");
  EXPECT_EQ(buildingSpecYaml(read), text);
  EXPECT_EQ(read.robot.motion, RobotMotion::kHandheld);
  EXPECT_DOUBLE_EQ(read.robot.walk_speed, 1.15);
  EXPECT_DOUBLE_EQ(read.robot.stair_speed, 0.5);
  EXPECT_DOUBLE_EQ(read.robot.handheld_gait.frequency, 1.7);
  EXPECT_DOUBLE_EQ(read.robot.handheld_gait.bounce, 0.025);
  EXPECT_DOUBLE_EQ(read.robot.handheld_gait.sway, 0.02);
  EXPECT_NEAR(read.robot.handheld_gait.roll, 0.03, 1e-15);
  EXPECT_NEAR(read.robot.handheld_gait.pitch, 0.02, 1e-15);
  EXPECT_NEAR(read.robot.handheld_gait.yaw, 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(read.robot.handheld_gait.slope_pitch, 0.25);
  EXPECT_EQ(read.sensors.lidar.model, LidarModel::kOs1_64);
  EXPECT_DOUBLE_EQ(read.sensors.lidar.rotation_rate, 20.0);
  ASSERT_TRUE(read.sensors.imu.grade);
  EXPECT_EQ(*read.sensors.imu.grade, ImuGrade::kConsumer);
  EXPECT_DOUBLE_EQ(read.sensors.imu.rate, 150.0);
  EXPECT_EQ(read.sensors.imu.gyro_noise_density, spec.sensors.imu.gyro_noise_density);
  EXPECT_EQ(read.sensors.imu.accel_bias, spec.sensors.imu.accel_bias);
  EXPECT_TRUE(read.sensors.imu.orientation);
  EXPECT_TRUE(
      read.sensors.imu.orientation_sigma.isApprox(Eigen::Vector3d(0.01, 0.02, 0.09), 1e-15));
  EXPECT_TRUE(read.sensors.T_body_lidar.isApprox(spec.sensors.T_body_lidar, 1e-15, 1e-15));
  EXPECT_TRUE(read.sensors.T_body_imu.isApprox(spec.sensors.T_body_imu, 1e-15, 1e-15));
  // Every model's name.
  for (LidarModel m :
       {LidarModel::kVlp16, LidarModel::kVlp32c, LidarModel::kHdl32e, LidarModel::kOs1_64}) {
    BuildingSpec s = loadBuildingSpec("tiny");
    s.sensors.lidar.model = m;
    EXPECT_EQ(parseBuildingSpec(buildingSpecYaml(s), "model").sensors.lidar.model, m);
  }
  // The legged defaults write motion: legged and grade: custom.
  const std::string legged = buildingSpecYaml(loadBuildingSpec("tiny"));
  EXPECT_NE(legged.find("motion: legged"), std::string::npos);
  EXPECT_NE(legged.find("grade: custom"), std::string::npos);
  EXPECT_NE(legged.find("orientation: false"), std::string::npos);
}

/// motion and grade set the defaults of their section; the keys given beside
/// them override those.
TEST(SimSpec, MotionAndGradeSetDefaultsThatKeysOverride) {
  const BuildingSpec hand = parseBuildingSpec(
      "robot:\n  motion: handheld\n  walk_speed: 1.3\n  handheld_gait: {bounce: 0.018}\n"
      "sensors:\n  imu: {grade: consumer, rate_hz: 120, orientation: true}\n"
      "  lidar: {model: VLP-32C}\n",
      "test");
  const RobotSpec defaults = robotForMotion(RobotMotion::kHandheld);
  EXPECT_EQ(hand.robot.motion, RobotMotion::kHandheld);
  EXPECT_DOUBLE_EQ(hand.robot.walk_speed, 1.3);
  EXPECT_DOUBLE_EQ(hand.robot.stair_speed, defaults.stair_speed);
  EXPECT_DOUBLE_EQ(hand.robot.body_height, defaults.body_height);
  EXPECT_DOUBLE_EQ(hand.robot.max_yaw_rate, 90.0 * M_PI / 180.0);
  EXPECT_DOUBLE_EQ(hand.robot.handheld_gait.bounce, 0.018);
  EXPECT_DOUBLE_EQ(hand.robot.handheld_gait.frequency, 1.9);
  const ImuSpec consumer = imuGrade(ImuGrade::kConsumer, 120.0);
  EXPECT_DOUBLE_EQ(hand.sensors.imu.rate, 120.0);
  EXPECT_EQ(hand.sensors.imu.gyro_noise_density, consumer.gyro_noise_density);
  EXPECT_EQ(hand.sensors.imu.accel_random_walk, consumer.accel_random_walk);
  EXPECT_EQ(hand.sensors.imu.gyro_bias, consumer.gyro_bias);
  EXPECT_TRUE(hand.sensors.imu.orientation);
  EXPECT_EQ(hand.sensors.lidar.model, LidarModel::kVlp32c);
  // Without motion and grade: the legged robot and the custom IMU of old.
  const BuildingSpec plain = parseBuildingSpec("name: plain\n", "test");
  EXPECT_EQ(plain.robot.motion, RobotMotion::kLegged);
  EXPECT_FALSE(plain.sensors.imu.grade);
  EXPECT_FALSE(plain.sensors.imu.orientation);
  EXPECT_EQ(plain.sensors.lidar.model, LidarModel::kVlp16);
}

TEST(SimSpec, BadSensorAndMotionValuesNameTheirKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"robot:\n  motion: wheeled\n", "robot.motion"},
      {"sensors:\n  lidar:\n    model: generic\n", "sensors.lidar.model"},
      {"sensors:\n  lidar:\n    model: VLS-128\n", "sensors.lidar.model"},
      {"sensors:\n  lidar: {model: OS1-64, rotation_rate_hz: 15}\n",
       "sensors.lidar.rotation_rate_hz"},
      {"sensors:\n  imu:\n    grade: navigation\n", "sensors.imu.grade"},
      {"sensors:\n  imu: {grade: tactical, rate_hz: 100}\n", "sensors.imu.rate_hz"},
      {"sensors:\n  imu: {grade: consumer, rate_hz: 400}\n", "sensors.imu.rate_hz"},
      {"sensors:\n  imu: {orientation_sigma_deg: [1, -1, 1]}\n",
       "sensors.imu.orientation_sigma_deg"},
      {"robot:\n  handheld_gait: {frequency_hz: 6}\n", "robot.handheld_gait.frequency_hz"},
      {"robot:\n  handheld_gait: {slope_pitch: 1.5}\n", "robot.handheld_gait.slope_pitch"},
      {"robot:\n  handheld_gait: {yaw_deg: 20}\n", "robot.handheld_gait.yaw_deg"},
      {"robot:\n  rounds: 0\n", "robot.rounds"},
  };
  for (const auto& [yaml, key] : cases) {
    try {
      parseBuildingSpec(yaml, "bad.yaml");
      ADD_FAILURE() << "no error for\n" << yaml;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    }
  }
  // The motions' names.
  for (RobotMotion m : {RobotMotion::kLegged, RobotMotion::kHandheld})
    EXPECT_EQ(robotMotionFromString(toString(m)), m);
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
        Expect{"building-a", 5, 350, 460, 450, 1100}, Expect{"building-b", 6, 540, 680, 700, 1500},
        Expect{"long-walk", 6, 1900, 2100, 3300, 3900}}) {
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
