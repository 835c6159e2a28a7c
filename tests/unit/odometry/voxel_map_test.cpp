#include "odometry/voxel_map.h"

#include "odometry/scan_matcher.h"

#include "common/parallel_chunks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  map.insert({{0.1f, 0.1f, 0.1f},
              {0.15f, 0.1f, 0.1f},
              {0.5f, 0.5f, 0.5f},
              {0.7f, 0.7f, 0.7f},
              {0.9f, 0.9f, 0.9f},
              {20.5f, 0.5f, 0.5f}});
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

TEST(VoxelMap, LargestFaceFitsTheTreadNotTheStepsSlope) {
  // Eight neighbours of a tread point near a stair's nosing: five on the
  // tread (z = 0), three on the riser below it (y = 0). One plane through
  // all eight passes the 5 cm tolerance but slopes 27 deg along the flight.
  const std::vector<Eigen::Vector3f> step = {
      {0.0f, 0.05f, 0.0f},  {0.1f, 0.12f, 0.0f},  {-0.1f, 0.16f, 0.0f},   {0.2f, 0.22f, 0.0f},
      {-0.2f, 0.09f, 0.0f}, {0.1f, 0.0f, -0.05f}, {-0.15f, 0.0f, -0.12f}, {0.2f, 0.0f, -0.09f}};
  const PlaneFit slope = fitPlane(step, 0.05);
  ASSERT_TRUE(slope.valid);
  EXPECT_LT(std::abs(slope.normal.z()), std::cos(15.0 * M_PI / 180.0));

  std::uint32_t face = 0;
  const PlaneFit tread = fitPlaneLargestFace(step.data(), 8, 0.05, 5, &face);
  ASSERT_TRUE(tread.valid);
  EXPECT_GT(std::abs(tread.normal.z()), std::cos(3.0 * M_PI / 180.0));
  EXPECT_EQ(face, 0x1Fu) << "the tread's points, not the riser's";
  EXPECT_FALSE(fitPlaneLargestFace(step.data(), 8, 0.05, 7).valid) << "no face of 7";
  // A query on the tread gets the tread; one a riser's height above it (on
  // the next tread up, whose points are not among these) gets no face.
  const Eigen::Vector3f on_tread(0.05f, 0.1f, 0.01f), next_tread(0.05f, 0.1f, 0.17f);
  EXPECT_TRUE(fitPlaneLargestFace(step.data(), 8, 0.05, 5, nullptr, &on_tread).valid);
  EXPECT_FALSE(fitPlaneLargestFace(step.data(), 8, 0.05, 5, nullptr, &next_tread).valid);

  // One surface with the points' noise (up to 2 cm): every point is on the
  // face and the plane is fitPlane's plane of them all.
  const float noise[8] = {0.012f, -0.02f, 0.015f, -0.005f, 0.02f, -0.016f, 0.0f, -0.011f};
  std::vector<Eigen::Vector3f> wall;
  for (int i = 0; i < 8; ++i)
    wall.emplace_back(2.0f + noise[i], 0.1f * i, 0.07f * static_cast<float>((i * 5) % 7));
  const PlaneFit all = fitPlane(wall, 0.05);
  const PlaneFit largest = fitPlaneLargestFace(wall.data(), 8, 0.05, 5, &face);
  ASSERT_TRUE(all.valid);
  ASSERT_TRUE(largest.valid);
  EXPECT_EQ(face, 0xFFu);
  EXPECT_NEAR(largest.normal.dot(all.normal), 1.0, 1e-12);
  EXPECT_NEAR(largest.d, all.d, 1e-12);
}

TEST(VoxelMap, KeepsViewDirectionsTowardsTheSensor) {
  VoxelMapConfig config;
  config.min_point_spacing = 0.0;
  VoxelMap map(config);
  map.insert({{1.0f, 0.0f, 0.0f}}, Eigen::Vector3d(1.0, 0.0, 2.0));  // seen from 2 m above
  map.insert({{1.2f, 0.0f, 0.0f}});                                  // no sensor: no view
  Eigen::Vector3f points[2], views[2];
  ASSERT_EQ(map.nearest({1.0f, 0.0f, 0.0f}, 2, 0.5f, points, views), 2);
  EXPECT_TRUE(views[0].isApprox(Eigen::Vector3f::UnitZ()));
  EXPECT_TRUE(views[1].isZero());
  // A rotation of the map rotates the views with the points.
  map.transform(Pose(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX())),
                     Eigen::Vector3d(0, 0, 5)));
  ASSERT_EQ(map.nearest({1.0f, 0.0f, 5.0f}, 1, 0.1f, points, views), 1);
  EXPECT_TRUE(views[0].isApprox(-Eigen::Vector3f::UnitY(), 1e-6f)) << views[0].transpose();
}

// A floor slab 0.25 m thick: its underside (z = -0.25) was mapped from the
// storey below. A point of its top face (z = 0) seen from above lies within
// the neighbour radius of the underside's points, which fit a plane: without
// the view directions it would be matched to the underside, a slab thickness
// away (the odometry then slid down by the slab thickness at stair landings).
TEST(ScanMatcher, TheSameMatchesOnTwoThreadsAsOnOne) {
  // Planar features are matched in chunks of 256 joined in order: with more
  // than one chunk, the same matches and rejects whatever the threads.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  VoxelMapConfig map_config;
  VoxelMap plane_map(map_config), edge_map(map_config);
  std::vector<Eigen::Vector3f> map_points;
  for (int i = 0; i < 20000; ++i) {
    const float a = u(rng), b = u(rng);
    map_points.emplace_back(a, b, 0.0f);             // floor
    map_points.emplace_back(a, 4.0f, b);             // wall
    map_points.emplace_back(a, b, 0.3f * a + 2.0f);  // slanted roof
  }
  plane_map.insert(map_points, Eigen::Vector3d(0, 0, 1));
  std::vector<Eigen::Vector3d> features;
  for (int i = 0; i < 1500; ++i)
    features.emplace_back(u(rng), u(rng), i % 3 == 0 ? 0.01 : (i % 3 == 1 ? 1.0 : 3.0));
  OdometryConfig config;
  const Pose T(Eigen::Quaterniond(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ())),
               Eigen::Vector3d(0.02, -0.01, 0.0));
  const ParallelChunks one(1), two(2);
  const MatchResult a =
      matchFeatures(features, {}, T, plane_map, edge_map, config, Eigen::Vector3d::Zero(), &one);
  const MatchResult b =
      matchFeatures(features, {}, T, plane_map, edge_map, config, Eigen::Vector3d::Zero(), &two);
  ASSERT_GT(a.planes.size(), 300u);
  ASSERT_EQ(a.planes.size(), b.planes.size());
  for (std::size_t i = 0; i < a.planes.size(); ++i) {
    EXPECT_EQ(a.planes[i].y_imu, b.planes[i].y_imu) << i;
    EXPECT_EQ(a.planes[i].n_world, b.planes[i].n_world) << i;
    EXPECT_EQ(a.planes[i].d_world, b.planes[i].d_world) << i;
    EXPECT_EQ(a.planes[i].sigma, b.planes[i].sigma) << i;
  }
  EXPECT_EQ(a.rejected, b.rejected);
  EXPECT_GT(a.rejected[static_cast<std::size_t>(MatchReject::kTooFewNeighbours)], 0);
}

TEST(ScanMatcher, RejectsPointsSeenFromTheOtherSideOfASlab) {
  std::vector<Eigen::Vector3f> underside;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j) underside.emplace_back(0.1f * i, 0.1f * j, -0.25f);
  OdometryConfig config;
  VoxelMap with_views(config.local_map), without_views(config.local_map);
  with_views.insert(underside, Eigen::Vector3d(0.0, 0.0, -1.5));  // seen from below
  without_views.insert(underside);
  const VoxelMap no_edges(config.local_map);
  const std::vector<Eigen::Vector3d> top_point{{0.02, 0.01, 0.0}};  // IMU frame = world here

  // Sensor above the slab (the point's own view): the underside is the other side.
  const Eigen::Vector3d sensor_above(0.0, 0.0, 1.0);
  MatchResult m = matchFeatures(top_point, {}, Pose(), with_views, no_edges, config, sensor_above);
  EXPECT_TRUE(m.planes.empty());
  EXPECT_EQ(m.rejected[static_cast<std::size_t>(MatchReject::kOtherSide)], 1);
  // Seen from below, the same point is on the mapped side and matches.
  m = matchFeatures(top_point, {}, Pose(), with_views, no_edges, config, Eigen::Vector3d(0, 0, -1));
  ASSERT_EQ(m.planes.size(), 1u);
  EXPECT_NEAR(std::abs(m.planes[0].n_world.z()), 1.0, 1e-6);
  // A map without view directions cannot tell (the old behaviour).
  m = matchFeatures(top_point, {}, Pose(), without_views, no_edges, config, sensor_above);
  EXPECT_EQ(m.planes.size(), 1u);
}

TEST(ScanMatcher, TheLargestFaceMatchesATreadPointToItsTread) {
  // The map holds a tread (z = 0) and the riser below its nosing (y = 0);
  // the fit of all eight slopes along the flight (VoxelMap.LargestFace...).
  OdometryConfig config;
  config.local_map.min_point_spacing = 0.0;
  VoxelMap map(config.local_map);
  map.insert({{0.0f, 0.05f, 0.0f},
              {0.1f, 0.12f, 0.0f},
              {-0.1f, 0.16f, 0.0f},
              {0.2f, 0.22f, 0.0f},
              {-0.2f, 0.09f, 0.0f},
              {0.1f, 0.0f, -0.05f},
              {-0.15f, 0.0f, -0.12f},
              {0.2f, 0.0f, -0.09f}});
  const VoxelMap no_edges(config.local_map);
  const std::vector<Eigen::Vector3d> tread_point{{0.05, 0.1, 0.01}};
  const Eigen::Vector3d sensor(0.0, 1.0, 1.2);
  MatchResult m = matchFeatures(tread_point, {}, Pose(), map, no_edges, config, sensor);
  ASSERT_EQ(m.planes.size(), 1u);
  EXPECT_LT(std::abs(m.planes[0].n_world.z()), std::cos(15.0 * M_PI / 180.0)) << "by default";
  config.plane_fit_min_inliers = 5;
  m = matchFeatures(tread_point, {}, Pose(), map, no_edges, config, sensor);
  ASSERT_EQ(m.planes.size(), 1u);
  EXPECT_GT(std::abs(m.planes[0].n_world.z()), std::cos(3.0 * M_PI / 180.0));
  EXPECT_NEAR(m.planes[0].d_world, 0.0, 0.005) << "the tread's plane, z = 0";
  // A point a riser higher (on the next tread, not in this map) finds no face.
  const std::vector<Eigen::Vector3d> next_tread{{0.05, 0.1, 0.17}};
  m = matchFeatures(next_tread, {}, Pose(), map, no_edges, config, sensor);
  EXPECT_TRUE(m.planes.empty());
  EXPECT_EQ(m.rejected[static_cast<std::size_t>(MatchReject::kNotPlanar)], 1);
}

}  // namespace
}  // namespace storey
