#pragma once
/// `storey simulate`: building spec -> building mesh, a legged robot's or a
/// person's walk, LiDAR (VLP-16, VLP-32C, HDL-32E, OS1-64) and IMU logs in a
/// ROS1 bag and/or (Velodyne models) a Velodyne capture (pcap) with an IMU
/// CSV, ground truth. See docs/simulator.md.
///
/// World frame of every output: z up (gravity (0, 0, -g)), x = the robot's
/// initial heading, origin at the LiDAR's start position.
#include <cstdint>
#include <string>
#include <vector>

#include "common/progress.h"
#include "sim/building_spec.h"
#include "sim/mcap_writer.h"
#include "sim/sim_faults.h"

namespace storey::sim {

/// File names inside the output folder.
inline constexpr const char* kBagFile = "simulation.bag";
/// ROS 2 bag folder (formats.ros2): metadata.yaml + simulation_ros2_0.db3 or .mcap.
inline constexpr const char* kRos2BagDir = "simulation_ros2";
/// The LiDAR topic when it carries packets (formats.packets).
inline constexpr const char* kPacketsTopic = "/velodyne_packets";
inline constexpr const char* kPcapFile = "simulation.pcap";  ///< Velodyne capture (formats.pcap)
inline constexpr const char* kImuCsvFile = "imu.csv";        ///< its IMU (formats.pcap)
/// LiDAR ground truth at the stamps of the capture's frames (formats.pcap).
/// Also the ground truth of the frames of VelodyneScan packets (formats.packets).
inline constexpr const char* kPcapLidarTruthFile = "groundtruth_lidar_pcap.tum";
inline constexpr const char* kLidarTruthFile = "groundtruth_lidar.tum";
inline constexpr const char* kImuTruthFile = "groundtruth_imu.tum";
inline constexpr const char* kMeshFile = "building.ply";
inline constexpr const char* kStoreysFile = "storeys.yaml";
inline constexpr const char* kCalibrationFile = "calibration.yaml";
/// The spec simulated (every key): `storey simulate spec.yaml` reproduces the folder.
inline constexpr const char* kSpecFile = "spec.yaml";

enum class Ros2Format { kNone, kDb3, kMcap };

/// Which logs to write (at least one).
struct SimulationFormats {
  bool bag = true;    ///< simulation.bag: ROS1 bag with the point clouds and the IMU
  bool pcap = false;  ///< simulation.pcap + imu.csv: the Velodyne LiDAR's UDP packets as VeloView
                      ///< records them, and the IMU
  Ros2Format ros2 = Ros2Format::kNone;  ///< simulation_ros2/: a ROS 2 bag (CDR messages)
  McapCompression mcap_compression = McapCompression::kZstd;  ///< MCAP chunks
  /// The LiDAR as velodyne_msgs/VelodyneScan packets on kPacketsTopic (in the
  /// ROS1 and ROS 2 bags) instead of point clouds; Velodyne models only.
  bool packets = false;
};

struct SimulationOptions {
  SimulationFormats formats;
  bool perfect_sensors = false;  ///< no noise, dropouts or biases (tests)
  double max_duration = 0.0;     ///< stop the sensors after this time; 0 = the whole walk [s]
  /// Leave out everything before this time: the logs (and their ground truth)
  /// start in the middle of the walk, as a log cut from a longer recording
  /// does (no still start when it is past the walk's still time) [s], >= 0.
  double start_at = 0.0;
  bool compress = true;  ///< LZ4 chunks in the bag
  int threads = 0;       ///< ray-casting threads; 0 = all cores
  /// Faults injected into the logs (not into the ground truth); LiDAR gaps
  /// only with point clouds (not with pcap or packets).
  std::vector<SimFault> faults;
};

struct SimulationResult {
  std::string out_dir;
  double duration = 0.0;       ///< simulated time [s]
  double walk_duration = 0.0;  ///< the whole planned walk [s]
  double path_length = 0.0;    ///< planned walking distance [m]
  std::int64_t scans = 0;
  std::int64_t points = 0;
  std::int64_t imu_samples = 0;
  std::int64_t pcap_packets = 0;  ///< data packets in simulation.pcap (0 without it)
  std::size_t triangles = 0;
  int storeys = 0;
  double wall_time = 0.0;  ///< [s]
};

/// Runs the simulation and writes the output folder (created if missing; its
/// files are replaced). Everything is written in a temporary folder next to
/// `out_dir` and moved in at the end, so a failure or a cancel (ProgressFn
/// returning false -> storey::Cancelled) leaves no partial output. Same spec
/// and options -> byte-identical files.
SimulationResult simulate(const BuildingSpec& spec, const SimulationOptions& options,
                          const std::string& out_dir, const ProgressFn& progress = {});

}  // namespace storey::sim
