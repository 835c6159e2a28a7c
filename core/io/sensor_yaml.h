#pragma once
/// YAML readers and writers of the sensor description shared by the config
/// file (under `sensor:`) and the calibration file (at its top level).
/// Used by io/calibration_file.cpp and config/.
#include <yaml-cpp/yaml.h>

#include "common/yaml_section.h"
#include "types/sensor.h"

namespace storey {

/// {translation: [x, y, z], rotation_xyzw: [x, y, z, w]}; both keys required.
/// The quaternion must have unit norm within 1e-3 (then it is normalised).
Pose readPose(YamlSection& section);
void readImuNoise(YamlSection& section, ImuNoise& imu);
void readLidarModel(YamlSection& section, const std::string& key, LidarModel& model);

void writePose(YAML::Emitter& out, const Pose& pose);
void writeImuNoise(YAML::Emitter& out, const ImuNoise& imu);

}  // namespace storey
