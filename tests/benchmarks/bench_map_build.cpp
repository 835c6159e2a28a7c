// The map stage's build: map scans placed at their poses and merged into
// the map's 2 cm voxels (MapBuilder::build), on 1 and 2 threads (the same
// cloud). 300 scans of 20,000 points on the surfaces of a 30 m x 20 m x 3 m
// storey (walls every 5 m, 1 cm noise), taken every 0.3 m along a loop, as
// the pipeline stores them (in a temporary file): about 6 M points into
// about 3 M voxels.
//   build/release/tests/benchmarks/bench_map_build --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "map/map_builder.h"

namespace storey {
namespace {

constexpr int kScans = 300;
constexpr int kPointsPerScan = 20000;

/// A point on the storey's floor, ceiling, outer or inner walls (world).
Eigen::Vector3d pointOnStorey(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  const double x = 30.0 * u(rng), y = 20.0 * u(rng), z = 3.0 * u(rng);
  switch (std::uniform_int_distribution<int>(0, 3)(rng)) {
    case 0:
      return {x, y, noise(rng)};  // floor
    case 1:
      return {x, y, 3.0 + noise(rng)};  // ceiling
    case 2:
      return {5.0 * std::floor(x / 5.0) + noise(rng), y, z};  // walls across x
    default:
      return {x, 5.0 * std::floor(y / 5.0) + noise(rng), z};  // walls across y
  }
}

struct Fixture {
  MapBuilder builder;
  std::vector<Pose> T_world_lidar;

  explicit Fixture(int threads) : builder(config(threads)) {
    std::mt19937 rng(7);
    for (int s = 0; s < kScans; ++s) {
      const double a = 2.0 * M_PI * s / kScans;
      const Pose T(Eigen::Quaterniond(Eigen::AngleAxisd(a + 0.3, Eigen::Vector3d::UnitZ())),
                   Eigen::Vector3d(15.0 + 10.0 * std::cos(a), 10.0 + 6.0 * std::sin(a), 1.5));
      Scan scan;
      scan.stamp_ns = 1'000'000'000LL + s * 100'000'000LL;
      for (int i = 0; i < kPointsPerScan; ++i) {
        ScanPoint p;
        p.p = (T.inverse() * pointOnStorey(rng)).cast<float>();
        p.intensity = 10.0f;
        p.time = 1e-5f * static_cast<float>(i % 10000);
        scan.points.push_back(p);
      }
      builder.addScan(s, scan);
      T_world_lidar.push_back(T);
    }
  }

  static MapConfig config(int threads) {
    MapConfig c;
    c.build_threads = threads;
    return c;
  }
};

void BM_MapBuild(benchmark::State& state) {
  Fixture fixture(static_cast<int>(state.range(0)));
  std::size_t points = 0;
  for (auto _ : state) {
    const MapCloud cloud = fixture.builder.build(fixture.T_world_lidar);
    points = cloud.size();
    benchmark::DoNotOptimize(points);
  }
  state.SetItemsProcessed(state.iterations() * fixture.builder.stats().points_stored);
  state.counters["map_points"] = static_cast<double>(points);
}
BENCHMARK(BM_MapBuild)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace storey

BENCHMARK_MAIN();
