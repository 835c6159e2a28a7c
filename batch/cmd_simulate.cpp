// `storey simulate`: a building spec (preset or YAML) -> ROS1 bag + ground truth.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "common/error.h"
#include "sim/simulator.h"

namespace storey::cli {
namespace {

/// A bar redrawn in place on a terminal; plain lines at 10 % steps otherwise.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool enabled) : enabled_(enabled), tty_(::isatty(STDERR_FILENO) == 1) {}
  ~ProgressPrinter() { finish(); }

  bool operator()(double fraction, const std::string& stage) {
    if (!enabled_) return true;
    const int percent = static_cast<int>(fraction * 100.0);
    if (tty_) {
      constexpr int kWidth = 40;
      const int filled = static_cast<int>(fraction * kWidth);
      std::cerr << "\r[" << std::string(filled, '#') << std::string(kWidth - filled, ' ') << "] "
                << std::setw(3) << percent << "% " << std::left << std::setw(20) << stage
                << std::right << std::flush;
      drawn_ = true;
    } else if (percent / 10 != last_decile_ || stage != last_stage_) {
      std::cerr << "storey simulate: " << percent << "% " << stage << '\n';
      last_decile_ = percent / 10;
      last_stage_ = stage;
    }
    return true;
  }
  void finish() {
    if (drawn_) std::cerr << '\n';
    drawn_ = false;
  }

 private:
  bool enabled_, tty_;
  bool drawn_ = false;
  int last_decile_ = -1;
  std::string last_stage_;
};

}  // namespace

int runSimulate(const SimulateOptions& options) {
  sim::BuildingSpec spec = sim::loadBuildingSpec(options.preset_or_spec);
  if (options.seed) spec.seed = *options.seed;
  if (options.range_noise) spec.sensors.lidar.range_noise = *options.range_noise;
  if (options.imu_rate_hz) spec.sensors.imu.rate = *options.imu_rate_hz;
  spec.validate();

  ProgressPrinter printer(options.progress);
  sim::SimulationOptions sim_options;
  sim_options.perfect_sensors = options.perfect_sensors;
  sim_options.compress = options.compress;
  sim_options.max_duration = options.max_duration.value_or(0.0);
  sim_options.threads = options.threads;
  if (sim_options.max_duration < 0.0) throw Error("--duration must be positive");
  if (sim_options.threads < 0) throw Error("--threads must be 0 (all cores) or more");
  const sim::SimulationResult result = sim::simulate(
      spec, sim_options, options.out_dir,
      [&](double fraction, const std::string& stage) { return printer(fraction, stage); });
  printer.finish();

  std::cout << std::fixed << std::setprecision(1) << "simulated '" << spec.name << "' (seed "
            << spec.seed << "): " << result.storeys << " storeys, " << result.path_length
            << " m walked in " << result.duration << " s; " << result.scans << " scans, "
            << result.points << " points, " << result.imu_samples << " IMU samples; "
            << std::setprecision(1) << result.wall_time << " s wall time ("
            << result.duration / std::max(result.wall_time, 1e-9) << "x real time)\n"
            << "output: " << result.out_dir << '\n';
  return 0;
}

}  // namespace storey::cli
