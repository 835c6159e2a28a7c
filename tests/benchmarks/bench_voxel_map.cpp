// The odometry's local map: k nearest neighbours of feature points (the
// matching's main cost), on one core. The map holds the surfaces of a
// 10 m x 8 m x 3 m room densely sampled (as the odometry inserts scan after
// scan: at most 20 points a 0.5 m voxel, 0.1 m apart); queries are points on
// those surfaces with 1 cm noise, 8 neighbours within 0.5 m as the odometry asks.
//   build/release/tests/benchmarks/bench_voxel_map --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>

#include "odometry/voxel_map.h"

namespace storey {
namespace {

Eigen::Vector3f pointOnRoom(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::uniform_int_distribution<int> face(0, 5);
  const Eigen::Vector3f size(10.0f, 8.0f, 3.0f);
  Eigen::Vector3f p(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z());
  const int f = face(rng);
  p[f / 2] = (f % 2) ? size[f / 2] : 0.0f;
  return p;
}

void BM_VoxelMapNearest(benchmark::State& state) {
  std::mt19937 rng(3);
  VoxelMap map{VoxelMapConfig{}};
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 200000; ++i) points.push_back(pointOnRoom(rng));
  map.insert(points, Eigen::Vector3d(5.0, 4.0, 1.5));
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::vector<Eigen::Vector3f> queries;
  for (int i = 0; i < 1000; ++i)
    queries.push_back(pointOnRoom(rng) + Eigen::Vector3f(noise(rng), noise(rng), noise(rng)));
  Eigen::Vector3f out[VoxelMap::kMaxNeighbours], views[VoxelMap::kMaxNeighbours];
  std::int64_t found = 0;
  for (auto _ : state) {
    for (const Eigen::Vector3f& q : queries) found += map.nearest(q, 8, 0.5f, out, views);
    benchmark::DoNotOptimize(found);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(queries.size()));
  state.counters["map_points"] = static_cast<double>(map.pointCount());
}
BENCHMARK(BM_VoxelMapNearest);

}  // namespace
}  // namespace storey

BENCHMARK_MAIN();
