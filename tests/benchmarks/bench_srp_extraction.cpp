// SRP extraction (the back end's per-keyframe cost) on simulated scans, one core.
//   build/release/tests/benchmarks/bench_srp_extraction --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
// The scans come from 30 s of a simulated preset (STOREY_BENCH_PRESET, `default`:
// VLP-16; `random:2`: OS1-64), every 10th scan, in the LiDAR frame as the
// back end gets them (not deskewed: the cost does not depend on it).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include "backend/srp_extraction.h"
#include "config/config.h"
#include "io/log_reader.h"
#include "sim/simulator.h"

namespace storey {
namespace {

struct Scans {
  Config config;
  std::vector<std::vector<Eigen::Vector3f>> scans;
};

const Scans& benchmarkScans() {
  static const Scans scans = [] {
    const char* preset_env = std::getenv("STOREY_BENCH_PRESET");
    const std::string preset = preset_env ? preset_env : "default";
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        ("storey-bench-srp-" + std::to_string(std::random_device{}()));
    sim::SimulationOptions options;
    options.compress = false;
    options.max_duration = 30.0;
    sim::simulate(sim::loadBuildingSpec(preset), options, dir.string());
    Scans result;
    result.config = loadRunConfig("", (dir / sim::kCalibrationFile).string());
    auto reader =
        openLog((dir / sim::kBagFile).string(), result.config.input, result.config.sensor);
    LogMessage message;
    for (int k = 0; reader->next(message);) {
      const auto* scan = std::get_if<Scan>(&message);
      if (!scan || k++ % 10 != 0) continue;
      std::vector<Eigen::Vector3f> points;
      points.reserve(scan->points.size());
      for (const ScanPoint& p : scan->points) points.push_back(p.p);
      result.scans.push_back(std::move(points));
    }
    std::filesystem::remove_all(dir);
    return result;
  }();
  return scans;
}

void BM_SrpExtractionPerKeyframe(benchmark::State& state) {
  const Scans& scans = benchmarkScans();
  std::size_t planes = 0;
  for (auto _ : state) {
    for (const auto& points : scans.scans) {
      const backend::SrpExtractionResult r =
          backend::extractSrps(points, scans.config.backend.extraction);
      planes += r.srps.size();
    }
  }
  benchmark::DoNotOptimize(planes);
  state.counters["scans"] = static_cast<double>(scans.scans.size());
  state.counters["ms_per_scan"] = benchmark::Counter(
      static_cast<double>(scans.scans.size()) * static_cast<double>(state.iterations()) * 1e-3,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SrpExtractionPerKeyframe)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace storey

BENCHMARK_MAIN();
