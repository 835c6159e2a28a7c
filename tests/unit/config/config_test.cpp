#include "config/config.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <set>

#include "common/error.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

const std::string kDefaultConfig =
    std::string(STOREY_SOURCE_DIR) + "/resources/config/default.yaml";

void collectLeafKeys(const YAML::Node& node, const std::string& prefix,
                     std::set<std::string>& keys) {
  if (!node.IsMap()) {
    keys.insert(prefix);
    return;
  }
  for (const auto& entry : node) {
    const std::string key = entry.first.as<std::string>();
    collectLeafKeys(entry.second, prefix.empty() ? key : prefix + "." + key, keys);
  }
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Config, DefaultFileHasEveryKeyAndTheStructDefaults) {
  const Config loaded = loadConfig(kDefaultConfig);
  EXPECT_EQ(configToYaml(loaded), configToYaml(Config{}))
      << "resources/config/default.yaml and the structs' defaults disagree";
  std::set<std::string> file_keys, struct_keys;
  collectLeafKeys(YAML::LoadFile(kDefaultConfig), "", file_keys);
  collectLeafKeys(YAML::Load(configToYaml(Config{})), "", struct_keys);
  EXPECT_EQ(file_keys, struct_keys) << "every parameter must be in default.yaml";
  EXPECT_GE(struct_keys.size(), 14u);  // the fixture itself is not trivially empty
}

TEST(Config, PartialFileOverridesOnlyItsKeys) {
  Config config;
  applyConfigYaml(config, "sensor:\n  imu:\n    rate_hz: 200\ninput:\n  imu_topic: /imu\n",
                  "t.yaml");
  EXPECT_EQ(config.sensor.imu.rate_hz, 200.0);
  EXPECT_EQ(config.input.imu_topic, "/imu");
  EXPECT_EQ(config.sensor.imu.gravity, 9.81);
  EXPECT_EQ(config.input.points_topic, "");
}

TEST(Config, EmptyFileKeepsDefaults) {
  Config config;
  applyConfigYaml(config, "", "empty.yaml");
  EXPECT_EQ(configToYaml(config), configToYaml(Config{}));
}

TEST(Config, UnknownKeyIsNamedWithFileLineAndSuggestion) {
  Config config;
  const std::string message =
      errorOf([&] { applyConfigYaml(config, "sensor:\n  imu:\n    rate_hx: 200\n", "my.yaml"); });
  EXPECT_NE(message.find("my.yaml"), std::string::npos) << message;
  EXPECT_NE(message.find("sensor.imu.rate_hx"), std::string::npos) << message;
  EXPECT_NE(message.find("line 3"), std::string::npos) << message;
  EXPECT_NE(message.find("sensor.imu.rate_hz"), std::string::npos) << message;
}

TEST(Config, UnknownTopLevelSection) {
  Config config;
  const std::string message = errorOf([&] { applyConfigYaml(config, "odometri: {}\n", "c.yaml"); });
  EXPECT_NE(message.find("unknown key 'odometri'"), std::string::npos) << message;
}

TEST(Config, AKeyThatIsNotANameIsAnError) {
  // Found by the fuzz run (tests/data/fuzz/config_yaml/complex_key.yaml): a
  // YAML complex key threw yaml-cpp's BadConversion instead of an error.
  Config config;
  const std::string message =
      errorOf([&] { applyConfigYaml(config, "input:\n  ? [a, b]\n  : 1\n", "c.yaml"); });
  EXPECT_NE(message.find("c.yaml: a key under 'input' is not a name"), std::string::npos)
      << message;
  EXPECT_NE(message.find("line 2"), std::string::npos) << message;
}

TEST(Config, MistypedValueIsNamed) {
  Config config;
  std::string message =
      errorOf([&] { applyConfigYaml(config, "input:\n  max_range: far\n", "c.yaml"); });
  EXPECT_NE(message.find("input.max_range"), std::string::npos) << message;
  EXPECT_NE(message.find("must be a number"), std::string::npos) << message;
  message = errorOf([&] {
    applyConfigYaml(
        config, "sensor:\n  T_imu_lidar:\n    translation: [1, 2]\n    rotation_xyzw: [0,0,0,1]\n",
        "c.yaml");
  });
  EXPECT_NE(message.find("sensor.T_imu_lidar.translation"), std::string::npos) << message;
  message =
      errorOf([&] { applyConfigYaml(config, "sensor:\n  lidar:\n    model: VLP16\n", "c.yaml"); });
  EXPECT_NE(message.find("sensor.lidar.model"), std::string::npos) << message;
  message = errorOf([&] { applyConfigYaml(config, "sensor: 3\n", "c.yaml"); });
  EXPECT_NE(message.find("'sensor'"), std::string::npos) << message;
  message =
      errorOf([&] { applyConfigYaml(config, "sensor:\n  imu:\n    rate_hz: -5\n", "c.yaml"); });
  EXPECT_NE(message.find("must be positive"), std::string::npos) << message;
}

TEST(Config, NegativeFeatureBudgetIsNamed) {
  Config config;
  const std::string message =
      errorOf([&] { applyConfigYaml(config, "odometry:\n  max_matched_planes: -1\n", "c.yaml"); });
  EXPECT_NE(message.find("odometry.max_matched_planes"), std::string::npos) << message;
  EXPECT_NE(message.find("must be >= 0"), std::string::npos) << message;
  applyConfigYaml(config, "odometry:\n  max_matched_planes: 0\n", "c.yaml");
  EXPECT_EQ(config.odometry.max_matched_planes, 0);
}

TEST(Config, InvalidYamlNamesLine) {
  Config config;
  const std::string message =
      errorOf([&] { applyConfigYaml(config, "input:\n  min_range: [1,\n", "broken.yaml"); });
  EXPECT_NE(message.find("broken.yaml"), std::string::npos) << message;
  EXPECT_NE(message.find("line"), std::string::npos) << message;
}

TEST(Config, RangeValidation) {
  Config config;
  const std::string message = errorOf(
      [&] { applyConfigYaml(config, "input:\n  min_range: 5\n  max_range: 2\n", "c.yaml"); });
  EXPECT_NE(message.find("input.max_range"), std::string::npos) << message;
  for (const char* angle : {"360", "-1"}) {
    Config c;
    const std::string cut = errorOf([&] {
      applyConfigYaml(c, std::string("input:\n  velodyne_cut_angle_deg: ") + angle + "\n",
                      "c.yaml");
    });
    EXPECT_NE(cut.find("input.velodyne_cut_angle_deg"), std::string::npos) << cut;
  }
  Config ok;
  applyConfigYaml(ok, "input:\n  velodyne_cut_angle_deg: 180\n", "c.yaml");
  EXPECT_EQ(ok.input.velodyne_cut_angle_deg, 180.0);
}

TEST(Config, MissingFileIsNamed) {
  const std::string message = errorOf([] { loadConfig("/nonexistent/storey.yaml"); });
  EXPECT_NE(message.find("/nonexistent/storey.yaml"), std::string::npos) << message;
}

TEST(Config, ExtrinsicRotationIsReadAsXyzw) {
  Config config;
  applyConfigYaml(config,
                  "sensor:\n  T_imu_lidar:\n    translation: [0.1, 0.2, 0.3]\n"
                  "    rotation_xyzw: [0.0, 0.0, 0.70710678, 0.70710678]\n",
                  "c.yaml");
  const Eigen::Vector3d x = config.sensor.T_imu_lidar * Eigen::Vector3d::UnitX();
  EXPECT_TRUE(x.isApprox(Eigen::Vector3d(0.1, 1.2, 0.3), 1e-7)) << x.transpose();
}

}  // namespace
}  // namespace storey
