// Odometry speed on a simulated VLP-16 + IMU log, on one core.
//   build/release/tests/benchmarks/bench_odometry --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
// The log (preset `default` by default; STOREY_BENCH_PRESET overrides, e.g.
// tiny) is simulated once into a temporary folder and read into memory, so
// the benchmark times the odometry alone: IMU preintegration, deskew,
// features, association and the joint optimisation of every scan.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include "config/config.h"
#include "io/log_reader.h"
#include "odometry/odometry.h"
#include "sim/simulator.h"

namespace storey {
namespace {

struct Log {
  Config config;
  std::vector<LogMessage> messages;
  std::int64_t scans = 0;
};

const Log& benchmarkLog() {
  static const Log log = [] {
    const char* preset_env = std::getenv("STOREY_BENCH_PRESET");
    const std::string preset = preset_env ? preset_env : "default";
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        ("storey-bench-" + preset + "-" + std::to_string(std::random_device{}()));
    sim::SimulationOptions options;
    options.compress = false;
    // A slice of the walk is enough for a stable per-scan median.
    options.max_duration = 60.0;
    sim::simulate(sim::loadBuildingSpec(preset), options, dir.string());
    Log result;
    result.config = loadRunConfig("", (dir / sim::kCalibrationFile).string());
    auto reader =
        openLog((dir / sim::kBagFile).string(), result.config.input, result.config.sensor);
    LogMessage message;
    while (reader->next(message)) {
      if (std::holds_alternative<Scan>(message)) ++result.scans;
      result.messages.push_back(std::move(message));
    }
    std::filesystem::remove_all(dir);
    return result;
  }();
  return log;
}

/// Argument: odometry.plane_fit_min_inliers (0: the default, every neighbour
/// on the plane; 5: the neighbours' largest face of at least 5).
void BM_OdometryPerScan(benchmark::State& state) {
  const Log& log = benchmarkLog();
  OdometryConfig config = log.config.odometry;
  config.plane_fit_min_inliers = static_cast<int>(state.range(0));
  std::vector<double> total_ms;
  for (auto _ : state) {
    std::int64_t emitted = 0;
    LidarInertialOdometry odometry(config, log.config.sensor);
    OdometryResult r;
    auto drain = [&] {
      while (odometry.nextResult(r)) {
        ++emitted;
        total_ms.push_back(r.stats.ms_total);
      }
    };
    for (const LogMessage& message : log.messages) {
      if (const auto* scan = std::get_if<Scan>(&message)) {
        odometry.addScan(*scan);
      } else {
        odometry.addImu(std::get<ImuSample>(message));
      }
      drain();
    }
    odometry.finish();
    drain();
    benchmark::DoNotOptimize(emitted);
  }
  // Time per scan: the benchmark's own clock divided by the scans of one pass.
  state.counters["scans"] = static_cast<double>(log.scans);
  state.counters["ms_per_scan"] = benchmark::Counter(
      static_cast<double>(log.scans) * static_cast<double>(state.iterations()) * 1e-3,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  std::nth_element(total_ms.begin(), total_ms.begin() + total_ms.size() / 2, total_ms.end());
  state.counters["median_scan_ms"] = total_ms.empty() ? 0.0 : total_ms[total_ms.size() / 2];
}
BENCHMARK(BM_OdometryPerScan)->Arg(0)->Arg(5)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace storey

BENCHMARK_MAIN();
