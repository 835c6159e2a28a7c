#include "config/config.h"

#include <cmath>

#include "common/error.h"
#include "config/sensor_yaml.h"
#include "config/yaml_section.h"

namespace storey {

const char* toString(LidarModel model) {
  switch (model) {
    case LidarModel::kVlp16: return "VLP-16";
    case LidarModel::kHdl32e: return "HDL-32E";
    case LidarModel::kOs1_64: return "OS1-64";
    case LidarModel::kGeneric: return "generic";
  }
  return "generic";
}

LidarModel lidarModelFromString(const std::string& name) {
  for (LidarModel m : {LidarModel::kVlp16, LidarModel::kHdl32e, LidarModel::kOs1_64,
                       LidarModel::kGeneric}) {
    if (name == toString(m)) return m;
  }
  throw Error("must be one of VLP-16, HDL-32E, OS1-64, generic; got '" + name + "'");
}

namespace {

void readSensor(YamlSection sensor, SensorConfig& config) {
  YamlSection pose = sensor.section("T_imu_lidar");
  if (sensor.has("T_imu_lidar")) config.T_imu_lidar = readPose(pose);
  sensor.read("time_offset_lidar_to_imu", config.time_offset_lidar_to_imu);
  YamlSection imu = sensor.section("imu");
  readImuNoise(imu, config.imu);
  YamlSection lidar = sensor.section("lidar");
  readLidarModel(lidar, "model", config.lidar_model);
  lidar.finish();
  sensor.finish();
}

void readInput(YamlSection input, InputConfig& config) {
  input.read("points_topic", config.points_topic);
  input.read("imu_topic", config.imu_topic);
  input.read("min_range", config.min_range);
  input.read("max_range", config.max_range);
  input.finish();
}

}  // namespace

void applyConfigYaml(Config& config, const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = parseYaml(yaml_text, source);
  YamlSection top(root, source, "");
  readSensor(top.section("sensor"), config.sensor);
  readInput(top.section("input"), config.input);
  top.finish();
  try {
    config.validate();
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
}

std::string configToYaml(const Config& config) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "sensor" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "T_imu_lidar" << YAML::Value;
  writePose(out, config.sensor.T_imu_lidar);
  out << YAML::Key << "time_offset_lidar_to_imu" << YAML::Value
      << config.sensor.time_offset_lidar_to_imu;
  out << YAML::Key << "imu" << YAML::Value;
  writeImuNoise(out, config.sensor.imu);
  out << YAML::Key << "lidar" << YAML::Value << YAML::BeginMap << YAML::Key << "model"
      << YAML::Value << toString(config.sensor.lidar_model) << YAML::EndMap;
  out << YAML::EndMap;
  out << YAML::Key << "input" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "points_topic" << YAML::Value << config.input.points_topic;
  out << YAML::Key << "imu_topic" << YAML::Value << config.input.imu_topic;
  out << YAML::Key << "min_range" << YAML::Value << config.input.min_range;
  out << YAML::Key << "max_range" << YAML::Value << config.input.max_range;
  out << YAML::EndMap;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

Config loadConfig(const std::string& path) {
  Config config;
  applyConfigYaml(config, readTextFile(path), path);
  return config;
}

void Config::validate() const {
  if (!(input.min_range >= 0.0)) throw Error("key 'input.min_range' must be >= 0");
  if (!(input.max_range > input.min_range))
    throw Error("key 'input.max_range' must be larger than 'input.min_range'");
  if (std::abs(sensor.time_offset_lidar_to_imu) > 1.0)
    throw Error("key 'sensor.time_offset_lidar_to_imu' must be within [-1, 1] s");
  if (sensor.imu.rate_hz > 10000.0) throw Error("key 'sensor.imu.rate_hz' must be <= 10000");
}

}  // namespace storey
