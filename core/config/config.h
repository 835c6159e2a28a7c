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

/// Off-screen PNG renders of a run's output (render/, docs/renders.md).
struct RenderViews {
  bool elevation = true;     ///< elevation_front.png, elevation_side.png: whole building by storey
  bool storeys = true;       ///< storey_NN_top.png: each storey from above, coloured by height
  bool srp = true;           ///< srp_map.png: global SRPs as patches over the grey map, per storey
  bool keyframe = true;      ///< srp_keyframe_NNNN.png: one keyframe's SRPs
  bool trajectories = true;  ///< trajectories_front/top.png: estimate vs ground truth (needs --gt)
};

struct RenderConfig {
  bool enabled = true;                 ///< `storey run` renders at the end (`--no-render` clears it)
  int width = 1600;                    ///< image width [px], [320, 8192]
  int height = 1000;                   ///< image height [px], [240, 8192]
  RenderViews views;
  int max_display_points = 2000000;    ///< map points drawn at most (uniform subsample) [>= 1000]
  double point_size = 2.0;             ///< map point size [px], (0, 20]
  double line_width = 3.0;             ///< trajectory line width [px], (0, 20]
  int keyframe = -1;                   ///< keyframe of the SRP keyframe view; -1 = the one with most SRPs
  double keyframe_radius = 15.0;       ///< map shown around that keyframe (xy) [m, > 0]
  double srp_point_distance = 0.05;    ///< map points this close to an SRP patch get its colour [m, > 0]
  double ceiling_cut = 0.15;           ///< storey views leave out points above ceiling - this [m, >= 0]
};

struct Config {
  SensorConfig sensor;
  InputConfig input;
  OdometryConfig odometry;
  BackendConfig backend;
  MapConfig map;          ///< map assembly (map/map_config.h)
  StoreysConfig storeys;  ///< storey segmentation (storeys/storeys_config.h)
  RenderConfig render;    ///< off-screen PNG renders (render/)

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
