#include "types/sensor.h"

#include <algorithm>

#include <cmath>

#include "common/error.h"

namespace storey {

const char* toString(LidarModel model) {
  switch (model) {
    case LidarModel::kVlp16:
      return "VLP-16";
    case LidarModel::kVlp32c:
      return "VLP-32C";
    case LidarModel::kHdl32e:
      return "HDL-32E";
    case LidarModel::kOs1_64:
      return "OS1-64";
    case LidarModel::kGeneric:
      return "generic";
  }
  return "generic";
}

LidarModel lidarModelFromString(const std::string& name) {
  for (LidarModel m : {LidarModel::kVlp16, LidarModel::kVlp32c, LidarModel::kHdl32e,
                       LidarModel::kOs1_64, LidarModel::kGeneric}) {
    if (name == toString(m)) return m;
  }
  throw Error("must be one of VLP-16, VLP-32C, HDL-32E, OS1-64, generic; got '" + name + "'");
}

double imuGapThreshold(const ImuNoise& imu) { return std::max(5.0 / imu.rate_hz, 0.05); }

void SensorConfig::validate() const {
  if (!(std::abs(time_offset_lidar_to_imu) <= 1.0))
    throw Error("key 'sensor.time_offset_lidar_to_imu' must be within [-1, 1] s");
  if (!(imu.rate_hz <= 10000.0)) throw Error("key 'sensor.imu.rate_hz' must be <= 10000");
}

}  // namespace storey
