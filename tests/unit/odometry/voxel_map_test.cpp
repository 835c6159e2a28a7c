#include "odometry/voxel_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace storey {
namespace {

TEST(VoxelMap, NearestMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  std::vector<Eigen::Vector3f> points(20000);
  for (auto& p : points) p = Eigen::Vector3f(u(rng), u(rng), u(rng));
  VoxelMapConfig config;
  config.max_points_per_voxel = 1000;  // keep everything for the comparison
  config.min_point_spacing = 0.0;
  VoxelMap map(config);
  map.insert(points);
  ASSERT_EQ(map.pointCount(), points.size());
  for (int q = 0; q < 200; ++q) {
    const Eigen::Vector3f query(u(rng), u(rng), u(rng));
    const auto found = map.nearest(query, 5, 0.5f);
    std::vector<float> truth;
    for (const auto& p : points)
      if ((p - query).norm() <= 0.5f) truth.push_back((p - query).norm());
    std::sort(truth.begin(), truth.end());
    ASSERT_EQ(found.size(), std::min<std::size_t>(5, truth.size()));
    for (std::size_t i = 0; i < found.size(); ++i)
      EXPECT_FLOAT_EQ((found[i] - query).norm(), truth[i]);
  }
}

TEST(VoxelMap, CapacitySpacingAndRemoval) {
  VoxelMapConfig config;
  config.voxel_size = 1.0;
  config.max_points_per_voxel = 3;
  config.min_point_spacing = 0.1;
  config.max_range = 10.0;
  VoxelMap map(config);
  map.insert({{0.1f, 0.1f, 0.1f}, {0.15f, 0.1f, 0.1f}, {0.5f, 0.5f, 0.5f}, {0.7f, 0.7f, 0.7f},
              {0.9f, 0.9f, 0.9f}, {20.5f, 0.5f, 0.5f}});
  EXPECT_EQ(map.pointCount(), 4u);  // one too close, one over capacity
  EXPECT_EQ(map.voxelCount(), 2u);
  map.removeFar(Eigen::Vector3d::Zero());
  EXPECT_EQ(map.pointCount(), 3u);
  EXPECT_EQ(map.voxelCount(), 1u);
}

TEST(VoxelMap, PlaneAndLineFits) {
  std::vector<Eigen::Vector3f> wall;
  for (int i = 0; i < 5; ++i) wall.emplace_back(2.0f, 0.1f * i, 0.07f * (i % 3));
  const PlaneFit plane = fitPlane(wall, 0.01);
  ASSERT_TRUE(plane.valid);
  EXPECT_NEAR(std::abs(plane.normal.x()), 1.0, 1e-9);
  EXPECT_NEAR(plane.normal.x() * 2.0, plane.d, 1e-9);
  wall.back().x() += 0.2f;  // an outlier beyond max_distance
  EXPECT_FALSE(fitPlane(wall, 0.05).valid);

  std::vector<Eigen::Vector3f> line;
  for (int i = 0; i < 5; ++i) line.emplace_back(1.0f, 1.0f + 0.001f * (i % 2), 0.2f * i);
  EXPECT_FALSE(fitPlane(line, 0.05).valid) << "collinear points define no plane";
  const LineFit fit = fitLine(line, 3.0);
  ASSERT_TRUE(fit.valid);
  EXPECT_NEAR(std::abs(fit.direction.z()), 1.0, 1e-4);
  EXPECT_FALSE(fitLine({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, 3.0).valid);
}

}  // namespace
}  // namespace storey
