#include "io/sensor_yaml.h"

#include <cmath>
#include <sstream>

#include "common/error.h"

namespace storey {

Pose readPose(YamlSection& section) {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  std::vector<double> xyzw;
  section.require("translation", translation);
  if (!section.has("rotation_xyzw")) section.fail("rotation_xyzw", "is required but missing");
  section.read("rotation_xyzw", xyzw, 4);
  const Eigen::Quaterniond q(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
  if (std::abs(q.norm() - 1.0) > 1e-3) {
    std::ostringstream os;
    os << "must be a unit quaternion [x, y, z, w], but its norm is " << q.norm();
    section.fail("rotation_xyzw", os.str());
  }
  section.finish();
  return Pose(q, translation);
}

void readImuNoise(YamlSection& section, ImuNoise& imu) {
  struct Field {
    const char* key;
    double* value;
  };
  const Field fields[] = {{"rate_hz", &imu.rate_hz},
                          {"gyro_noise_density", &imu.gyro_noise_density},
                          {"accel_noise_density", &imu.accel_noise_density},
                          {"gyro_random_walk", &imu.gyro_random_walk},
                          {"accel_random_walk", &imu.accel_random_walk},
                          {"gravity", &imu.gravity}};
  for (const Field& f : fields) {
    section.read(f.key, *f.value);
    const bool is_density = f.value != &imu.rate_hz && f.value != &imu.gravity;
    if (section.has(f.key) && is_density && !(*f.value >= 0.0)) section.fail(f.key, "must be >= 0");
    if (section.has(f.key) && !is_density && !(*f.value > 0.0))
      section.fail(f.key, "must be positive");
  }
  section.finish();
}

void readLidarModel(YamlSection& section, const std::string& key, LidarModel& model) {
  std::string name;
  section.read(key, name);
  if (!section.has(key)) return;
  try {
    model = lidarModelFromString(name);
  } catch (const Error& e) {
    section.fail(key, e.what());
  }
}

void writePose(YAML::Emitter& out, const Pose& pose) {
  const Eigen::Vector3d& t = pose.translation();
  const Eigen::Quaterniond& q = pose.rotation();
  out << YAML::BeginMap;
  out << YAML::Key << "translation" << YAML::Value << YAML::Flow << YAML::BeginSeq << t.x() << t.y()
      << t.z() << YAML::EndSeq << YAML::Comment("metres");
  out << YAML::Key << "rotation_xyzw" << YAML::Value << YAML::Flow << YAML::BeginSeq << q.x()
      << q.y() << q.z() << q.w() << YAML::EndSeq
      << YAML::Comment("unit quaternion, Hamilton, x y z w");
  out << YAML::EndMap;
}

void writeImuNoise(YAML::Emitter& out, const ImuNoise& imu) {
  out << YAML::BeginMap;
  out << YAML::Key << "rate_hz" << YAML::Value << imu.rate_hz;
  out << YAML::Key << "gyro_noise_density" << YAML::Value << imu.gyro_noise_density
      << YAML::Comment("rad/s/sqrt(Hz)");
  out << YAML::Key << "accel_noise_density" << YAML::Value << imu.accel_noise_density
      << YAML::Comment("m/s^2/sqrt(Hz)");
  out << YAML::Key << "gyro_random_walk" << YAML::Value << imu.gyro_random_walk
      << YAML::Comment("rad/s^2/sqrt(Hz)");
  out << YAML::Key << "accel_random_walk" << YAML::Value << imu.accel_random_walk
      << YAML::Comment("m/s^3/sqrt(Hz)");
  out << YAML::Key << "gravity" << YAML::Value << imu.gravity << YAML::Comment("m/s^2");
  out << YAML::EndMap;
}

}  // namespace storey
