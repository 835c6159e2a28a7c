#include "odometry/features.h"

#include "common/parallel_chunks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace storey {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// An axis-aligned box room seen from inside, with an optional box pillar
/// (an occluder) standing on the floor.
struct Room {
  Eigen::Vector3d min, max;
  bool has_pillar = false;
  Eigen::Vector3d pillar_min = Eigen::Vector3d::Zero(), pillar_max = Eigen::Vector3d::Zero();
};

/// Ray against the inside of the room and the outside of the pillar.
double castRay(const Room& room, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  double best = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(dir[a]) < 1e-12) continue;
    for (double wall : {room.min[a], room.max[a]}) {
      const double t = (wall - origin[a]) / dir[a];
      if (t > 0 && t < best) best = t;
    }
  }
  if (room.has_pillar) {  // slab method
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      const double inv = 1.0 / dir[a];
      double ta = (room.pillar_min[a] - origin[a]) * inv,
             tb = (room.pillar_max[a] - origin[a]) * inv;
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 <= t1 && t0 > 0 && t0 < best) best = t0;
  }
  return best;
}

/// A VLP-16-like revolution from `origin` (no motion, no noise).
Scan scanRoom(const Room& room, const Eigen::Vector3d& origin) {
  Scan scan;
  for (int step = 0; step < 1800; ++step) {
    const double azimuth = step * 0.2 * kPi / 180.0;
    for (int ring = 0; ring < 16; ++ring) {
      const double elevation = (-15.0 + 2.0 * ring) * kPi / 180.0;
      const Eigen::Vector3d dir(std::cos(elevation) * std::cos(azimuth),
                                std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
      const double range = castRay(room, origin, dir);
      if (!std::isfinite(range) || range > 100.0) continue;
      ScanPoint p;
      p.p = (dir * range).cast<float>();
      p.ring = static_cast<std::uint16_t>(ring);
      p.time = static_cast<float>(step * 0.1 / 1800.0);
      scan.points.push_back(p);
    }
  }
  return scan;
}

double distanceToRoomSurface(const Room& room, const Eigen::Vector3d& x) {
  double d = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
    d = std::min({d, std::abs(x[a] - room.min[a]), std::abs(x[a] - room.max[a])});
  if (room.has_pillar) {
    // distance to the pillar's surface for points outside it
    const Eigen::Vector3d c = x.cwiseMax(room.pillar_min).cwiseMin(room.pillar_max);
    d = std::min(d, (x - c).norm());
  }
  return d;
}

/// Distance (horizontal) to the nearest vertical edge of the room or pillar.
double distanceToVerticalEdge(const Room& room, const Eigen::Vector3d& x) {
  double d = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector2d> corners;
  for (double cx : {room.min.x(), room.max.x()})
    for (double cy : {room.min.y(), room.max.y()}) corners.emplace_back(cx, cy);
  if (room.has_pillar)
    for (double cx : {room.pillar_min.x(), room.pillar_max.x()})
      for (double cy : {room.pillar_min.y(), room.pillar_max.y()}) corners.emplace_back(cx, cy);
  for (const auto& c : corners) d = std::min(d, (x.head<2>() - c).norm());
  return d;
}

TEST(Features, PlanarPointsLieOnSurfacesAndEdgesNearCorners) {
  Room room{{-3, -2.5, -1.2}, {5, 2.5, 1.8}, true, {1.5, -0.2, -1.2}, {1.9, 0.2, 1.8}};
  const Scan scan = scanRoom(room, Eigen::Vector3d::Zero());
  ASSERT_GT(scan.points.size(), 25000u);  // the fixture sees the whole room

  FeatureConfig config;
  config.plane_voxel_size = 0.0;  // keep the raw planar points to check them one by one
  config.edge_voxel_size = 0.0;
  config.max_edges_per_sector = 20;  // the odometry's default is planar features only
  const FeatureSet features = extractFeatures(scan, config);
  ASSERT_GT(features.planes.size(), 5000u);
  ASSERT_GT(features.edges.size(), 20u);

  for (const auto& p : features.planes)
    ASSERT_LT(distanceToRoomSurface(room, p.cast<double>()), 1e-4);
  // Planar points are not at corners: their neighbourhood lies on one plane.
  int planes_at_vertical_edges = 0;
  for (const auto& p : features.planes)
    if (distanceToVerticalEdge(room, p.cast<double>()) < 0.01) ++planes_at_vertical_edges;
  EXPECT_EQ(planes_at_vertical_edges, 0);

  // Edges: at a vertical edge or at the floor/ceiling-wall creases.
  int at_structure = 0;
  for (const auto& p : features.edges) {
    const Eigen::Vector3d x = p.cast<double>();
    const double to_crease =
        std::min(std::abs(x.z() - room.min.z()), std::abs(x.z() - room.max.z()));
    if (distanceToVerticalEdge(room, x) < 0.2 || to_crease < 0.2) ++at_structure;
  }
  EXPECT_GE(at_structure, static_cast<int>(0.9 * features.edges.size()))
      << at_structure << " of " << features.edges.size();
  // Every one of the room's four vertical corners yields edges.
  for (double cx : {room.min.x(), room.max.x()}) {
    for (double cy : {room.min.y(), room.max.y()}) {
      int near = 0;
      for (const auto& p : features.edges)
        if ((p.head<2>().cast<double>() - Eigen::Vector2d(cx, cy)).norm() < 0.2) ++near;
      EXPECT_GT(near, 0) << "corner " << cx << " " << cy;
    }
  }
  // The pillar occludes part of the far wall: the wall points beside its silhouette are rejected.
  EXPECT_GT(features.rejected[static_cast<int>(FeatureReject::kOccluded)], 16);
}

TEST(Features, TheSameFeaturesOnTwoThreadsAsOnOne) {
  // Rings are processed in parallel and joined in ring order: same vectors.
  Room room{{-3, -2.5, -1.2}, {5, 2.5, 1.8}, true, {1.5, -0.2, -1.2}, {1.9, 0.2, 1.8}};
  const Scan scan = scanRoom(room, Eigen::Vector3d(0.3, -0.2, 0.1));
  FeatureConfig config;
  config.max_edges_per_sector = 20;
  const ParallelChunks one(1), two(2);
  const FeatureSet a = extractFeatures(scan, config, &one);
  const FeatureSet b = extractFeatures(scan, config, &two);
  const FeatureSet c = extractFeatures(scan, config);
  ASSERT_GT(a.planes.size(), 100u);
  ASSERT_GT(a.edges.size(), 10u);
  EXPECT_EQ(a.planes, b.planes);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.rejected, b.rejected);
  EXPECT_EQ(a.plane_candidates, b.plane_candidates);
  EXPECT_EQ(a.edge_candidates, b.edge_candidates);
  EXPECT_EQ(a.planes, c.planes);
}

TEST(Features, GrazingWallsOfALongCorridorAreRejectedAsParallelBeams) {
  Room corridor{{-30, -1.0, -1.2}, {30, 1.0, 1.5}, false, {}, {}};
  const Scan scan = scanRoom(corridor, Eigen::Vector3d::Zero());
  const FeatureSet features = extractFeatures(scan, FeatureConfig{});
  EXPECT_GT(features.rejected[static_cast<int>(FeatureReject::kParallelBeam)], 100);
  EXPECT_GT(features.planes.size(), 100u);
}

TEST(Features, GapsInARingAreNotBridged) {
  Room room{{-4, -4, -1.2}, {4, 4, 2.0}, false, {}, {}};
  Scan scan = scanRoom(room, Eigen::Vector3d::Zero());
  // Remove a 10 deg wedge (glass): its borders must not be used as neighbours.
  std::vector<ScanPoint> kept;
  for (const auto& p : scan.points)
    if (!(p.time > 0.05f && p.time < 0.05f + 0.1f * 10.0f / 360.0f)) kept.push_back(p);
  const std::size_t removed = scan.points.size() - kept.size();
  ASSERT_GT(removed, 100u);
  scan.points = kept;
  const FeatureSet features = extractFeatures(scan, FeatureConfig{});
  // 16 rings x 2 borders x k=5 points next to the gap, plus both ends of each ring.
  EXPECT_GE(features.rejected[static_cast<int>(FeatureReject::kRingGap)], 16 * 2 * 5);
}

TEST(Features, VoxelDownsampleKeepsOnePointPerVoxel) {
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) points.emplace_back(0.01f * i, 0.01f * j, 0.05f);
  points.emplace_back(1.05f, 0.05f, 0.05f);
  const auto down = voxelDownsample(points, 0.1);
  ASSERT_EQ(down.size(), 2u);
  // the input point nearest to the centroid (0.045, 0.045) represents the voxel
  EXPECT_TRUE(down[0].isApprox(Eigen::Vector3f(0.04f, 0.04f, 0.05f), 1e-6f)) << down[0].transpose();
  EXPECT_NEAR(down[1].x(), 1.05f, 1e-6);
  // negative coordinates fall in their own voxels
  EXPECT_EQ(voxelDownsample({{-0.01f, 0, 0}, {0.01f, 0, 0}}, 0.1).size(), 2u);
}

}  // namespace
}  // namespace storey
