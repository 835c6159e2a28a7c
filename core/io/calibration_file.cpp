#include "io/calibration_file.h"

#include <yaml-cpp/yaml.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/yaml_section.h"
#include "io/sensor_yaml.h"

namespace storey {

Calibration readCalibrationFile(const std::string& path, const Calibration& base) {
  const std::string source = path + " (calibration)";
  const YAML::Node root = parseYaml(readTextFile(path), source);
  if (!root || root.IsNull()) throw Error(source + ": the file is empty");
  YamlSection top(root, source, "");

  Calibration result = base;
  YamlSection pose = top.section("T_imu_lidar");
  if (!top.has("T_imu_lidar")) top.fail("T_imu_lidar", "is required but missing");
  result.sensor.T_imu_lidar = readPose(pose);
  top.read("time_offset_lidar_to_imu", result.sensor.time_offset_lidar_to_imu);
  YamlSection imu = top.section("imu");
  readImuNoise(imu, result.sensor.imu);
  YamlSection lidar = top.section("lidar");
  readLidarModel(lidar, "model", result.sensor.lidar_model);
  lidar.read("cut_angle_deg", result.velodyne_cut_angle_deg);
  if (lidar.has("cut_angle_deg") &&
      !(result.velodyne_cut_angle_deg >= 0.0 && result.velodyne_cut_angle_deg < 360.0)) {
    lidar.fail("cut_angle_deg", "must be in [0, 360) degrees");
  }
  lidar.finish();
  YamlSection topics = top.section("topics");
  topics.read("points", result.points_topic);
  topics.read("imu", result.imu_topic);
  topics.finish();
  top.finish();
  try {
    result.sensor.validate();
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  return result;
}

void writeCalibrationFile(const Calibration& calibration, const std::string& path) {
  const SensorConfig& sensor = calibration.sensor;
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::Comment("Storey sensor calibration, format version 1");
  out << YAML::BeginMap;
  out << YAML::Key << "T_imu_lidar" << YAML::Comment("pose of the LiDAR frame in the IMU frame")
      << YAML::Value;
  writePose(out, sensor.T_imu_lidar);
  out << YAML::Key << "time_offset_lidar_to_imu" << YAML::Value << sensor.time_offset_lidar_to_imu
      << YAML::Comment("seconds; t_imu = t_lidar + offset");
  out << YAML::Key << "imu" << YAML::Value;
  writeImuNoise(out, sensor.imu);
  out << YAML::Key << "lidar" << YAML::Value << YAML::BeginMap << YAML::Key << "model"
      << YAML::Value << toString(sensor.lidar_model);
  if (calibration.velodyne_cut_angle_deg != 0.0) {
    out << YAML::Key << "cut_angle_deg" << YAML::Value << calibration.velodyne_cut_angle_deg
        << YAML::Comment("Velodyne packets: frames start at this azimuth (deg)");
  }
  out << YAML::EndMap;
  if (!calibration.points_topic.empty() || !calibration.imu_topic.empty()) {
    out << YAML::Key << "topics" << YAML::Value << YAML::BeginMap;
    if (!calibration.points_topic.empty())
      out << YAML::Key << "points" << YAML::Value << calibration.points_topic;
    if (!calibration.imu_topic.empty())
      out << YAML::Key << "imu" << YAML::Value << calibration.imu_topic;
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  if (!out.good()) throw Error(path + ": cannot format calibration: " + out.GetLastError());
  writeFileAtomically(path, std::string(out.c_str()) + "\n");
}

}  // namespace storey
