#include "config/calibration.h"

#include <yaml-cpp/yaml.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "config/sensor_yaml.h"
#include "config/yaml_section.h"

namespace storey {

void applyCalibrationFile(Config& config, const std::string& path) {
  const std::string source = path + " (calibration)";
  const YAML::Node root = parseYaml(readTextFile(path), source);
  if (!root || root.IsNull()) throw Error(source + ": the file is empty");
  YamlSection top(root, source, "");

  Config result = config;  // all or nothing: `config` is untouched on error
  YamlSection pose = top.section("T_imu_lidar");
  if (!top.has("T_imu_lidar")) top.fail("T_imu_lidar", "is required but missing");
  result.sensor.T_imu_lidar = readPose(pose);
  top.read("time_offset_lidar_to_imu", result.sensor.time_offset_lidar_to_imu);
  YamlSection imu = top.section("imu");
  readImuNoise(imu, result.sensor.imu);
  YamlSection lidar = top.section("lidar");
  readLidarModel(lidar, "model", result.sensor.lidar_model);
  lidar.finish();
  YamlSection topics = top.section("topics");
  topics.read("points", result.input.points_topic);
  topics.read("imu", result.input.imu_topic);
  topics.finish();
  top.finish();
  try {
    result.validate();
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  config = result;
}

Config loadRunConfig(const std::string& config_path, const std::string& calibration_path) {
  Config config = config_path.empty() ? Config{} : loadConfig(config_path);
  if (!calibration_path.empty()) applyCalibrationFile(config, calibration_path);
  return config;
}

void writeCalibrationFile(const Config& config, const std::string& path) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::Comment("Storey sensor calibration, format version 1");
  out << YAML::BeginMap;
  out << YAML::Key << "T_imu_lidar" << YAML::Comment("pose of the LiDAR frame in the IMU frame")
      << YAML::Value;
  writePose(out, config.sensor.T_imu_lidar);
  out << YAML::Key << "time_offset_lidar_to_imu" << YAML::Value
      << config.sensor.time_offset_lidar_to_imu << YAML::Comment("seconds; t_imu = t_lidar + offset");
  out << YAML::Key << "imu" << YAML::Value;
  writeImuNoise(out, config.sensor.imu);
  out << YAML::Key << "lidar" << YAML::Value << YAML::BeginMap << YAML::Key << "model"
      << YAML::Value << toString(config.sensor.lidar_model) << YAML::EndMap;
  if (!config.input.points_topic.empty() || !config.input.imu_topic.empty()) {
    out << YAML::Key << "topics" << YAML::Value << YAML::BeginMap;
    if (!config.input.points_topic.empty())
      out << YAML::Key << "points" << YAML::Value << config.input.points_topic;
    if (!config.input.imu_topic.empty())
      out << YAML::Key << "imu" << YAML::Value << config.input.imu_topic;
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  if (!out.good()) throw Error(path + ": cannot format calibration: " + out.GetLastError());
  writeFileAtomically(path, std::string(out.c_str()) + "\n");
}

}  // namespace storey
