// Map assembly: per-scan and global voxel downsampling, attributes, poses.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "common/error.h"
#include "map/map_builder.h"

namespace storey {
namespace {

ScanPoint point(float x, float y, float z, float intensity, float time) {
  ScanPoint p;
  p.p = Eigen::Vector3f(x, y, z);
  p.intensity = intensity;
  p.time = time;
  return p;
}

Scan makeScan(std::int64_t stamp_ns, std::vector<ScanPoint> points) {
  Scan scan;
  scan.stamp_ns = stamp_ns;
  scan.points = std::move(points);
  return scan;
}

class MapBuilderTest : public ::testing::TestWithParam<bool> {};

TEST_P(MapBuilderTest, VoxelCentroidIntensityMeanFirstTimeAndKeyframe) {
  MapConfig config;
  config.voxel_size = 0.1;
  config.spill_to_disk = GetParam();
  MapBuilder builder(config);
  // Keyframe 0: two points in one voxel, one in another.
  builder.addScan(0, makeScan(1'000'000'000, {point(1.01f, 0.01f, 0.01f, 10, 0.02f),
                                              point(1.03f, 0.03f, 0.03f, 20, -0.01f),
                                              point(2.05f, 0.05f, 0.05f, 5, 0.0f)}));
  // Keyframe 3 (indices need not be contiguous), sensor moved +1 m in x: its
  // point (0.02, 0.02, 0.02) lands in the first voxel in the world.
  builder.addScan(3, makeScan(2'000'000'000, {point(0.05f, 0.05f, 0.05f, 40, 0.0f)}));
  EXPECT_EQ(builder.stats().scans, 2);
  EXPECT_EQ(builder.stats().points_in, 4);
  EXPECT_EQ(builder.stats().points_stored, 3);  // per-scan voxels: 2 + 1

  std::vector<Pose> poses(4);
  poses[3] = Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.0, 0.0, 0.0));
  const MapCloud map = builder.build(poses);
  ASSERT_EQ(map.size(), 2u);
  // Fixture check: the first voxel got points of both keyframes.
  const Eigen::Vector3f first = map.positions[0];
  // Keyframe 0's voxel centroid (1.02, .02, .02) averaged with (1.05, .05, .05).
  EXPECT_NEAR(first.x(), (1.02 + 1.05) / 2, 1e-5);
  EXPECT_NEAR(first.z(), (0.02 + 0.05) / 2, 1e-5);
  EXPECT_NEAR(map.intensity[0], (15.0 + 40.0) / 2, 1e-4);  // mean of the per-scan means
  EXPECT_NEAR(map.time[0], 1.0 - 0.01, 1e-9);  // first keyframe's earliest point, absolute
  EXPECT_EQ(map.keyframe[0], 0);
  EXPECT_EQ(map.storey[0], kNoStorey);
  EXPECT_EQ(map.flags[0], 0);
  EXPECT_NEAR(map.positions[1].x(), 2.05, 1e-5);
  EXPECT_NEAR(map.intensity[1], 5.0, 1e-6);
}

TEST_P(MapBuilderTest, PosesAreAppliedAtBuildTimeAndCanChange) {
  MapConfig config;
  config.voxel_size = 0.02;
  config.spill_to_disk = GetParam();
  MapBuilder builder(config);
  builder.addScan(0, makeScan(0, {point(1.0f, 0.0f, 0.0f, 1, 0)}));
  const Pose yaw90(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())),
                   Eigen::Vector3d(0.0, 0.0, 2.0));
  MapCloud map = builder.build({yaw90});
  ASSERT_EQ(map.size(), 1u);
  EXPECT_NEAR(map.positions[0].x(), 0.0, 0.011);
  EXPECT_NEAR(map.positions[0].y(), 1.0, 0.011);
  EXPECT_NEAR(map.positions[0].z(), 2.0, 0.011);
  map = builder.build({Pose()});
  EXPECT_NEAR(map.positions[0].x(), 1.0, 0.011);
  // Adding after a build keeps working (the store is appended to).
  builder.addScan(1, makeScan(0, {point(5.0f, 0.0f, 0.0f, 1, 0)}));
  map = builder.build({Pose(), Pose()});
  ASSERT_EQ(map.size(), 2u);
  EXPECT_NEAR(map.positions[1].x(), 5.0, 0.011);
}

TEST_P(MapBuilderTest, DropsFarAndNonFinitePointsAndRejectsBadInput) {
  MapConfig config;
  config.max_range = 10.0;
  config.spill_to_disk = GetParam();
  MapBuilder builder(config);
  builder.addScan(
      0, makeScan(0, {point(11.0f, 0, 0, 1, 0), point(NAN, 0, 0, 1, 0), point(9.0f, 0, 0, 1, 0)}));
  EXPECT_EQ(builder.stats().points_beyond_range, 1);
  EXPECT_EQ(builder.stats().points_non_finite, 1);
  EXPECT_EQ(builder.stats().points_stored, 1);
  EXPECT_THROW(builder.addScan(0, makeScan(0, {})), Error);   // twice
  EXPECT_THROW(builder.addScan(-1, makeScan(0, {})), Error);  // negative
  builder.addScan(5, makeScan(0, {}));
  EXPECT_THROW(builder.build({Pose()}), Error);  // keyframe 5 has no pose
  EXPECT_EQ(builder.build(std::vector<Pose>(6)).size(), 1u);
  MapConfig bad;
  bad.voxel_size = 0.0;
  EXPECT_THROW(MapBuilder{bad}, Error);
}

TEST_P(MapBuilderTest, DenseSurfaceIsReducedToOnePointPerVoxel) {
  // A 1 m x 1 m wall sampled every 5 mm from two keyframes -> about 50 x 50
  // voxels of 2 cm in the map, whatever the number of scans.
  MapConfig config;
  config.spill_to_disk = GetParam();
  MapBuilder builder(config);
  for (int kf = 0; kf < 2; ++kf) {
    std::vector<ScanPoint> points;
    for (int i = 0; i < 200; ++i)
      for (int j = 0; j < 200; ++j)
        points.push_back(point(3.0f, 0.0025f + 0.005f * i, 0.0025f + 0.005f * j, 1, 0));
    builder.addScan(kf, makeScan(kf, points));
  }
  EXPECT_EQ(builder.stats().points_in, 80000);
  EXPECT_LE(builder.stats().points_stored, 2 * 51 * 51 * 2);
  const MapCloud map = builder.build({Pose(), Pose()});
  EXPECT_GE(map.size(), 50u * 50u);
  EXPECT_LE(map.size(), 51u * 51u * 2u);  // the plane x = 3 may straddle a voxel face
  for (const Eigen::Vector3f& p : map.positions) EXPECT_NEAR(p.x(), 3.0, 1e-4);
}

TEST_P(MapBuilderTest, EveryVoxelGetsItsPointsInOrderWhateverTheirNumber) {
  // Points at LiDAR voxel centres (kept as they are by the per-scan step),
  // scans turned 45 deg and shifted so that several points of one scan, near
  // each other in its order, share a world voxel; thousands of points per scan.
  // Reference: each point's voxel summed one point at a time, voxels in the
  // order first seen.
  MapConfig config;
  config.voxel_size = 0.02;
  config.spill_to_disk = GetParam();
  MapBuilder builder(config);
  std::vector<Pose> poses;
  std::vector<std::vector<ScanPoint>> scans;
  for (int s = 0; s < 3; ++s) {
    std::vector<ScanPoint> points;
    for (int i = 0; i < 60; ++i)
      for (int j = 0; j < 60; ++j)
        points.push_back(point(0.01f + 0.02f * static_cast<float>(i),
                               0.01f + 0.02f * static_cast<float>(j), 0.01f,
                               static_cast<float>((i * 7 + j * 3 + s) % 50), 0.0f));
    builder.addScan(s, makeScan(s, points));
    scans.push_back(points);
    poses.emplace_back(
        Eigen::Quaterniond(Eigen::AngleAxisd(0.785398 * (s + 1), Eigen::Vector3d::UnitZ())),
        Eigen::Vector3d(0.003 * s, 0.007 * s, 0.0));
  }
  ASSERT_EQ(builder.stats().points_stored, 3 * 60 * 60);
  struct Voxel {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double intensity = 0.0;
    int n = 0;
  };
  std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> order;
  std::map<std::tuple<std::int64_t, std::int64_t, std::int64_t>, Voxel> voxels;
  int shared = 0;
  for (std::size_t s = 0; s < scans.size(); ++s)
    for (const ScanPoint& sp : scans[s]) {
      const Eigen::Vector3d p = poses[s] * sp.p.cast<double>();
      const auto key = std::make_tuple(static_cast<std::int64_t>(std::floor(p.x() / 0.02)),
                                       static_cast<std::int64_t>(std::floor(p.y() / 0.02)),
                                       static_cast<std::int64_t>(std::floor(p.z() / 0.02)));
      Voxel& v = voxels[key];
      if (v.n == 0) order.push_back(key);
      shared += v.n > 0 ? 1 : 0;
      v.sum += p;
      v.intensity += sp.intensity;
      ++v.n;
    }
  ASSERT_GT(shared, 1000) << "fixture: points must share voxels";
  const MapCloud map = builder.build(poses);
  ASSERT_EQ(map.size(), order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Voxel& v = voxels[order[i]];
    ASSERT_NEAR((map.positions[i].cast<double>() - v.sum / v.n).norm(), 0.0, 2e-5) << "voxel " << i;
    ASSERT_NEAR(map.intensity[i], v.intensity / v.n, 1e-3) << "voxel " << i;
  }
}

TEST_P(MapBuilderTest, AnyNumberOfBuildThreadsGivesTheSameCloud) {
  // Scans that overlap (the same voxels seen again, in other orders) and
  // more points than one block, so voxels of every part interleave.
  std::vector<Scan> scans;
  std::vector<Pose> poses;
  std::uint32_t state = 12345;
  auto uniform = [&state]() {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / static_cast<float>(1u << 24);
  };
  for (int s = 0; s < 24; ++s) {
    std::vector<ScanPoint> points;
    for (int i = 0; i < 15000; ++i)
      points.push_back(point(4.0f * uniform(), 3.0f * uniform(), 0.5f * uniform(),
                             100.0f * uniform(), 0.1f * uniform()));
    scans.push_back(makeScan(1'000'000'000LL + s * 100'000'000LL, std::move(points)));
    poses.emplace_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * s, Eigen::Vector3d::UnitZ())),
                       Eigen::Vector3d(0.1 * s, 0.0, 0.01 * s));
  }
  std::vector<MapCloud> clouds;
  for (int threads : {1, 2, 3}) {
    MapConfig config;
    config.spill_to_disk = GetParam();
    config.build_threads = threads;
    MapBuilder builder(config);
    for (int s = 0; s < 24; ++s) builder.addScan(s, scans[static_cast<std::size_t>(s)], s / 4);
    clouds.push_back(builder.build(poses));
  }
  ASSERT_GT(clouds[0].size(), 100000u);
  for (std::size_t c = 1; c < clouds.size(); ++c) {
    ASSERT_EQ(clouds[c].size(), clouds[0].size());
    for (std::size_t i = 0; i < clouds[0].size(); ++i) {
      ASSERT_EQ(clouds[c].positions[i], clouds[0].positions[i]) << "point " << i;
      ASSERT_EQ(clouds[c].intensity[i], clouds[0].intensity[i]) << "point " << i;
      ASSERT_EQ(clouds[c].time[i], clouds[0].time[i]) << "point " << i;
      ASSERT_EQ(clouds[c].keyframe[i], clouds[0].keyframe[i]) << "point " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Storage, MapBuilderTest, ::testing::Values(true, false),
                         [](const auto& param_info) {
                           return param_info.param ? "Disk" : "Memory";
                         });

}  // namespace
}  // namespace storey
