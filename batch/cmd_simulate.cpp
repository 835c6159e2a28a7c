// `storey simulate`: a building spec (preset or YAML) -> ROS1 bag and/or Velodyne
// pcap + IMU CSV, with ground truth.

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "common/error.h"
#include "progress_bar.h"
#include "sim/random_spec.h"
#include "sim/simulator.h"

namespace storey::cli {

int runSimulate(const SimulateOptions& options) {
  sim::BuildingSpec spec = sim::loadBuildingSpec(options.preset_or_spec);
  sim::applyRigOverrides(spec, {options.lidar, options.imu, options.motion});
  if (options.seed) spec.seed = *options.seed;
  if (options.range_noise) spec.sensors.lidar.range_noise = *options.range_noise;
  if (options.imu_rate_hz) spec.sensors.imu.rate = *options.imu_rate_hz;
  spec.validate();

  ProgressBar bar("simulate", options.progress);
  sim::SimulationOptions sim_options;
  sim_options.perfect_sensors = options.perfect_sensors;
  sim_options.compress = options.compress;
  sim_options.max_duration = options.max_duration.value_or(0.0);
  sim_options.start_at = options.start_at;
  sim_options.threads = options.threads;
  sim_options.formats.bag = options.bag;
  sim_options.formats.pcap = options.pcap;
  sim_options.formats.packets = options.packets;
  for (const std::string& fault : options.faults)
    sim_options.faults.push_back(sim::parseSimFault(fault));
  if (options.ros2 == "db3") sim_options.formats.ros2 = sim::Ros2Format::kDb3;
  if (options.ros2 == "mcap") sim_options.formats.ros2 = sim::Ros2Format::kMcap;
  if (options.mcap_compression == "none")
    sim_options.formats.mcap_compression = sim::McapCompression::kNone;
  if (options.mcap_compression == "lz4")
    sim_options.formats.mcap_compression = sim::McapCompression::kLz4;
  if (!options.bag && !options.pcap && options.ros2.empty())
    throw Error("--no-bag needs --pcap or --ros2 (nothing would be written)");
  if (sim_options.max_duration < 0.0) throw Error("--duration must be positive");
  if (!(sim_options.start_at >= 0.0)) throw Error("--start-at must be 0 or more");
  if (sim_options.threads < 0) throw Error("--threads must be 0 (all cores) or more");
  const sim::SimulationResult result =
      sim::simulate(spec, sim_options, options.out_dir, bar.callback());
  bar.done();

  std::cout << std::fixed << std::setprecision(1) << "simulated '" << spec.name << "' (seed "
            << spec.seed << "): " << result.storeys << " storeys, " << result.path_length
            << " m walked in " << result.duration << " s; " << result.scans << " scans, "
            << result.points << " points, " << result.imu_samples << " IMU samples; "
            << std::setprecision(1) << result.wall_time << " s wall time ("
            << result.duration / std::max(result.wall_time, 1e-9) << "x real time)\n";
  if (options.pcap) std::cout << "Velodyne capture: " << result.pcap_packets << " data packets\n";
  if (!options.ros2.empty()) {
    std::cout << "ROS 2 bag: " << sim::kRos2BagDir << "/ (" << options.ros2
              << (options.ros2 == "mcap" ? ", " + options.mcap_compression + " chunks" : "")
              << ")\n";
  }
  std::cout << "output: " << result.out_dir << '\n';
  return 0;
}

}  // namespace storey::cli
