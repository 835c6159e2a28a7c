// The odometry's LiDAR factor, evaluated as Ceres does in its solve, on one
// core: one scan's point-to-plane matches (random planes and points, a
// VLP-16's and a 64-beam's match counts), with and without Jacobians.
//   build/release/tests/benchmarks/bench_lidar_factors --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <array>
#include <random>

#include "odometry/lidar_factors.h"

namespace storey {
namespace {

MatchResult randomMatches(int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MatchResult matches;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d y(10.0 * unit(rng), 10.0 * unit(rng), 2.0 * unit(rng));
    const Eigen::Vector3d n = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
    matches.planes.push_back({y, n, n.dot(y) + 0.02 * unit(rng), 0.03});
  }
  return matches;
}

void BM_CompressedScanFactor(benchmark::State& state) {
  const MatchResult matches = randomMatches(static_cast<int>(state.range(0)));
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const std::array<double, 7> pose{0.1, -0.2, 0.05, q.x(), q.y(), q.z(), q.w()};
  const CompressedScanFactor factor(matches, pose.data(), 1.345);
  const double* parameters[] = {pose.data()};
  std::array<double, 8> residuals{};
  std::array<double, 8 * 7> jacobian{};
  double* jacobians[] = {state.range(1) ? jacobian.data() : nullptr};
  for (auto _ : state) {
    factor.Evaluate(parameters, residuals.data(), jacobians);
    benchmark::DoNotOptimize(residuals);
    benchmark::DoNotOptimize(jacobian);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_CompressedScanFactor)
    ->ArgNames({"planes", "jacobian"})
    ->Args({700, 1})
    ->Args({700, 0})
    ->Args({2700, 1})
    ->Args({2700, 0});

}  // namespace
}  // namespace storey

BENCHMARK_MAIN();
