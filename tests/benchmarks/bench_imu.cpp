// Google Benchmark of the IMU maths on the synthetic trot of the unit tests
// (tests/unit/imu/synthetic_imu.h), 400 Hz: pose-table queries (deskew),
// building a scan's pose table, the IMU factor's Evaluate with every
// Jacobian, and re-propagating a 0.1 s preintegration. Speed is measured
// here, not by timed unit tests.
//   build/release/tests/benchmarks/bench_imu --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "imu/imu_factor.h"
#include "imu/imu_pose_table.h"
#include "imu/imu_preintegration.h"
#include "imu/imu_state_blocks.h"
#include "synthetic_imu.h"

namespace storey {
namespace {

std::int64_t ns(double seconds) {
  return test::kBaseNs + secondsToNs(seconds);
}

const test::SyntheticTrajectory& trot() {
  static const test::SyntheticTrajectory tr = test::SyntheticTrajectory::trot();
  return tr;
}

const std::vector<ImuSample>& samples() {
  static const std::vector<ImuSample> s = test::simulateImu(trot(), test::ImuSimOptions());
  return s;
}

void BM_PoseTableQuery(benchmark::State& state) {
  const ImuPoseTable table =
      ImuPoseTable::fromSamples(trot().state(ns(0.1)), samples(), ns(0.2), 9.81);
  std::vector<double> times(4096);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uni(0.0, 0.1);
  for (double& t : times) t = uni(rng);
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::Quaterniond q;
    Eigen::Vector3d p;
    table.interpolate(times[i++ % times.size()], q, p);
    benchmark::DoNotOptimize(p);
    benchmark::DoNotOptimize(q);
  }
}
BENCHMARK(BM_PoseTableQuery);

void BM_PoseTableBuild(benchmark::State& state) {  // one 0.1 s scan at 400 Hz
  for (auto _ : state) {
    const ImuPoseTable table =
        ImuPoseTable::fromSamples(trot().state(ns(0.1)), samples(), ns(0.2), 9.81);
    benchmark::DoNotOptimize(table.endState().v_world_imu);
  }
}
BENCHMARK(BM_PoseTableBuild);

void BM_ImuFactorEvaluate(benchmark::State& state) {  // residual and every Jacobian
  const ImuPreintegration pre =
      ImuPreintegration::fromSamples(samples(), ns(0.31), ns(0.41), ImuBias(), ImuNoise());
  const ImuFactor factor(pre);
  const ImuStateBlocks bi = ImuStateBlocks::fromState(trot().state(ns(0.31)));
  const ImuStateBlocks bj = ImuStateBlocks::fromState(trot().state(ns(0.41)));
  const double* params[4] = {bi.pose, bi.motion, bj.pose, bj.motion};
  double r[15], j0[15 * 7], j1[15 * 9], j2[15 * 7], j3[15 * 9];
  double* jacobians[4] = {j0, j1, j2, j3};
  for (auto _ : state) {
    factor.Evaluate(params, r, jacobians);
    benchmark::DoNotOptimize(r[0]);
    benchmark::DoNotOptimize(j3[0]);
  }
}
BENCHMARK(BM_ImuFactorEvaluate);

void BM_Repropagate(benchmark::State& state) {  // 0.1 s at 400 Hz
  const ImuPreintegration pre =
      ImuPreintegration::fromSamples(samples(), ns(0.31), ns(0.41), ImuBias(), ImuNoise());
  for (auto _ : state) {
    ImuPreintegration p = pre;
    p.repropagate(ImuBias());
    benchmark::DoNotOptimize(p.deltas().dv);
  }
}
BENCHMARK(BM_Repropagate);

}  // namespace
}  // namespace storey

BENCHMARK_MAIN();
