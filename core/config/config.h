#pragma once
/// Every parameter of the pipeline, one plain struct per stage with its
/// defaults in the struct and units beside each field. The YAML file
/// (resources/config/default.yaml), the CLI and the plugin only fill these.
#include <string>

#include "backend/backend_config.h"
#include "map/map_config.h"
#include "odometry/odometry_config.h"
#include "storeys/storeys_config.h"
#include "types/pose.h"

namespace storey {

/// LiDAR models known to the readers (ring elevations, firing timing).
enum class LidarModel { kVlp16, kHdl32e, kOs1_64, kGeneric };
const char* toString(LidarModel model);
/// Parses "VLP-16", "HDL-32E", "OS1-64", "generic"; throws storey::Error otherwise.
LidarModel lidarModelFromString(const std::string& name);

/// Noise model of the IMU (continuous-time densities, as on datasheets).
struct ImuNoise {
  double rate_hz = 400.0;                ///< nominal sample rate [Hz], (0, 10000]
  double gyro_noise_density = 1.75e-4;   ///< [rad/s/sqrt(Hz)]
  double accel_noise_density = 5.9e-4;   ///< [m/s^2/sqrt(Hz)]
  double gyro_random_walk = 1.0e-5;      ///< gyro bias random walk [rad/s^2/sqrt(Hz)]
  double accel_random_walk = 1.0e-4;     ///< accel bias random walk [m/s^3/sqrt(Hz)]
  double gravity = 9.81;                 ///< magnitude of gravity [m/s^2]
};

/// The sensor set-up: what a calibration file describes.
struct SensorConfig {
  Pose T_imu_lidar;                       ///< pose of the LiDAR frame in the IMU frame
  double time_offset_lidar_to_imu = 0.0;  ///< [s]; t_imu = t_lidar + offset
  ImuNoise imu;
  LidarModel lidar_model = LidarModel::kVlp16;
};

/// How logs are read.
struct InputConfig {
  std::string points_topic;  ///< PointCloud2 topic; empty = auto-detect
  std::string imu_topic;     ///< Imu topic; empty = auto-detect
  double min_range = 0.3;    ///< points closer than this are dropped [m] (robot body, sensor head)
  double max_range = 120.0;  ///< points farther than this are dropped [m]
  // Velodyne pcap, PCD folder and IMU CSV inputs (docs/formats.md).
  std::string imu_csv;                ///< IMU CSV file; empty = none (PCD folder: imu.csv inside it)
  double imu_csv_time_offset = 0.0;   ///< added to the CSV's stamps to put them on the LiDAR clock [s]
  std::string velodyne_model = "auto";  ///< pcap: "auto" (from the packets), "VLP-16" or "HDL-32E"
  std::string velodyne_calibration;   ///< pcap: VeloView calibration XML; empty = the manual's table
  std::string pcap_clock = "sensor";  ///< pcap: "sensor" (packet timestamps) or "capture" (record times)
  int pcap_data_port = 2368;          ///< pcap: UDP port of data packets; 0 = any port
  int pcap_position_port = 8308;      ///< pcap: UDP port of position (IMU) packets; 0 = any port
};

/// The back end (SRP constraints, keyframe graph; backend/backend_config.h).
struct BackendConfig {
  bool srp = true;  ///< SRP back end on; off (`--no-srp`): trajectory = odometry
  KeyframeConfig keyframes;
  SrpExtractionConfig extraction;
  AssociationConfig association;
  GraphConfig graph;
};

struct Config {
  SensorConfig sensor;
  InputConfig input;
  OdometryConfig odometry;
  BackendConfig backend;
  MapConfig map;          ///< map assembly (map/map_config.h)
  StoreysConfig storeys;  ///< storey segmentation (storeys/storeys_config.h)

  /// Checks value ranges; throws storey::Error naming the key at fault.
  void validate() const;
};

/// Loads a configuration file over the defaults. Every key is optional; an
/// unknown key, a wrong type or a value out of range is a storey::Error that
/// names the file, the key and its line.
Config loadConfig(const std::string& path);
/// The whole configuration as YAML, every key present (the run report keeps
/// it; a test checks that resources/config/default.yaml has the same keys).
std::string configToYaml(const Config& config);
/// Applies a YAML text (same rules) over `config`; `source` names it in errors.
void applyConfigYaml(Config& config, const std::string& yaml_text, const std::string& source);

}  // namespace storey
