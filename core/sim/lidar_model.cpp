#include "sim/lidar_model.h"

#include <cmath>

#include "common/error.h"

namespace storey::sim {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

/// Ouster OS1-64-like: 64 beams evenly over 45 deg, 1024 columns per revolution.
constexpr int kOusterBeams = 64;
constexpr double kOusterTopDeg = 22.5;
constexpr int kOusterColumns = 1024;
constexpr double kOusterRangeStep = 0.001;  ///< the driver's `range` field is in mm

std::int64_t nanoseconds(double seconds) {
  return static_cast<std::int64_t>(std::llround(seconds * 1e9));
}

LidarBeams velodyneBeams(LidarModel model, velodyne::Model table) {
  const velodyne::Calibration calibration = velodyne::defaultCalibration(table);
  LidarBeams beams;
  beams.model = model;
  beams.layout = CloudLayout::kVelodyne;
  beams.sequence_period_ns = nanoseconds(velodyne::sequencePeriod(table));
  beams.distance_step = calibration.distance_resolution_m;
  for (std::size_t id = 0; id < calibration.lasers.size(); ++id) {
    const velodyne::Laser& laser = calibration.lasers[id];
    // Written as the VLP-16 code before it, (deg * pi) / 180, so its rays stay bit-identical.
    beams.elevation.push_back(laser.elevation_deg * M_PI / 180.0);
    // The decoder subtracts its rotational correction from the azimuth.
    beams.azimuth_offset.push_back(-laser.azimuth_offset_deg * kDegToRad);
    beams.firing_ns.push_back(
        nanoseconds(velodyne::laserFiringOffset(table, static_cast<int>(id))));
    beams.ring.push_back(laser.ring);
  }
  return beams;
}

LidarBeams ousterBeams() {
  LidarBeams beams;
  beams.model = LidarModel::kOs1_64;
  beams.layout = CloudLayout::kOuster;
  beams.columns = kOusterColumns;
  beams.distance_step = kOusterRangeStep;
  for (int row = 0; row < kOusterBeams; ++row) {
    const double elevation_deg = kOusterTopDeg - 2.0 * kOusterTopDeg * row / (kOusterBeams - 1);
    beams.elevation.push_back(elevation_deg * kDegToRad);
    beams.azimuth_offset.push_back(0.0);
    beams.firing_ns.push_back(0);
    beams.ring.push_back(static_cast<std::uint16_t>(kOusterBeams - 1 - row));
  }
  return beams;
}

}  // namespace

bool isSimulatedLidar(LidarModel model) {
  return model != LidarModel::kGeneric;
}

const char* simulatedLidarNames() {
  return "VLP-16, VLP-32C, HDL-32E, OS1-64";
}

std::optional<velodyne::Model> velodyneModel(LidarModel model) {
  switch (model) {
    case LidarModel::kVlp16:
      return velodyne::Model::kVlp16;
    case LidarModel::kVlp32c:
      return velodyne::Model::kVlp32c;
    case LidarModel::kHdl32e:
      return velodyne::Model::kHdl32e;
    case LidarModel::kOs1_64:
    case LidarModel::kGeneric:
      break;
  }
  return std::nullopt;
}

LidarBeams lidarBeams(LidarModel model) {
  if (const std::optional<velodyne::Model> table = velodyneModel(model))
    return velodyneBeams(model, *table);
  if (model == LidarModel::kOs1_64) return ousterBeams();
  throw Error(std::string("simulator: no model of the LiDAR '") + toString(model) +
              "' (simulated: " + simulatedLidarNames() + ")");
}

}  // namespace storey::sim
