#include "sim/lidar_simulator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "sim/vlp16.h"
#include "sim/world.h"
#include "unit/sim/scan_on_mesh.h"

namespace storey::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct TinyFixture {
  BuildingSpec spec = loadBuildingSpec("tiny");
  World world = makeWorld(spec);
};

const TinyFixture& tiny() {
  static const TinyFixture fixture;
  return fixture;
}

TEST(SimLidar, Vlp16FiringOrderAndRings) {
  const int expected[16] = {-15, 1, -13, 3, -11, 5, -9, 7, -7, 9, -5, 11, -3, 13, -1, 15};
  std::set<int> rings;
  for (int id = 0; id < 16; ++id) {
    EXPECT_EQ(vlp16::elevationDeg(id), expected[id]);
    EXPECT_EQ(vlp16::ring(id), (expected[id] + 15) / 2);
    rings.insert(vlp16::ring(id));
  }
  EXPECT_EQ(rings.size(), 16u);
  EXPECT_EQ(vlp16::ring(0), 0);
  EXPECT_EQ(vlp16::ring(15), 15);
  EXPECT_EQ(vlp16::kSequencePeriodNs,
            24 * vlp16::kFiringIntervalNs);  // 16 firings + 8 recharge slots
}

/// A scan taken while walking: rings, azimuth steps, timing, and every point
/// lying on the true mesh when placed with the true pose at its own time.
TEST(SimLidar, NoiseFreeScanMatchesTheSensorAndTheMesh) {
  const TinyFixture& f = tiny();
  const LidarSimulator lidar(f.world.building.mesh, f.world.trajectory, f.spec.sensors,
                             LidarNoise{}, 1);
  const int n = 60;  // 6 s: walking
  ASSERT_GT(f.world.trajectory.body(lidar.scanStampNs(n) * 1e-9).v_world.norm(), 0.3);
  const Scan scan = lidar.simulateScan(n);
  ASSERT_GT(scan.points.size(), 20000u);  // indoors most beams return (not through glass)
  EXPECT_LE(scan.points.size(), 1809u * 16u);
  EXPECT_EQ(scan.stamp_ns % vlp16::kSequencePeriodNs, 0);
  EXPECT_GE(scan.stamp_ns, n * 100'000'000LL);
  EXPECT_LT(scan.stamp_ns, n * 100'000'000LL + vlp16::kSequencePeriodNs);

  std::map<int, std::vector<const ScanPoint*>> by_ring;
  for (const ScanPoint& p : scan.points) {
    ASSERT_GE(p.time, 0.0f);
    ASSERT_LT(p.time, 0.1f);
    // Elevation of the point = its ring's elevation.
    const double elevation = std::atan2(p.p.z(), std::hypot(p.p.x(), p.p.y()));
    EXPECT_NEAR(elevation, (-15 + 2 * p.ring) * kDeg, 2e-6);
    by_ring[p.ring].push_back(&p);
  }
  ASSERT_EQ(by_ring.size(), 16u);
  // Azimuth steps between consecutive firings of one laser: 360 deg * 10 Hz * 55.296 us.
  const double step = 2 * M_PI * 10.0 * 55.296e-6;
  int steps = 0;
  for (const auto& [ring, points] : by_ring) {
    for (std::size_t i = 1; i < points.size(); ++i) {
      const double dt = points[i]->time - points[i - 1]->time;
      if (std::abs(dt - 55.296e-6) > 1e-8) continue;  // a dropout in between
      const double a0 = std::atan2(points[i - 1]->p.y(), points[i - 1]->p.x());
      const double a1 = std::atan2(points[i]->p.y(), points[i]->p.x());
      EXPECT_NEAR(std::remainder(a0 - a1, 2 * M_PI), step, 1e-5);  // clockwise: azimuth decreases
      ++steps;
    }
  }
  EXPECT_GT(steps, 20000);
  // Within a firing sequence the lasers fire 2.304 us apart, in laser-ID order.
  int within = 0;
  for (std::size_t i = 1; i < scan.points.size(); ++i) {
    const double dt = scan.points[i].time - scan.points[i - 1].time;
    const auto sequence = [](float t) { return std::floor(t / 55.296e-6 + 1e-3); };
    if (sequence(scan.points[i].time) != sequence(scan.points[i - 1].time)) continue;
    const int slots = static_cast<int>(std::lround(dt / 2.304e-6));
    EXPECT_NEAR(dt, slots * 2.304e-6, 2e-8);
    // Laser ID from the ring: elevation e < 0 -> id = e + 15, e > 0 -> id = e.
    const auto laser = [](int ring) {
      const int e = -15 + 2 * ring;
      return e < 0 ? e + 15 : e;
    };
    EXPECT_EQ(laser(scan.points[i].ring) - laser(scan.points[i - 1].ring), slots);
    ++within;
  }
  EXPECT_GT(within, 15000);

  // On the mesh, placed with the true pose at each point's own time.
  const Pose& T_body_lidar = f.spec.sensors.T_body_lidar;
  EXPECT_LT(worstDistanceToMesh(f.world, scan, T_body_lidar, 29), 1e-3);
  // ...but not with the scan's stamp pose: the scan really is motion-distorted.
  double distorted = 0.0;
  const Pose T_stamp = f.world.trajectory.frame(scan.stamp_ns * 1e-9, T_body_lidar).T_world_frame;
  for (std::size_t i = scan.points.size() - 2000; i < scan.points.size(); i += 7)
    distorted = std::max(
        distorted, f.world.building.mesh.distanceTo(T_stamp * scan.points[i].p.cast<double>()));
  EXPECT_GT(distorted, 0.03);
}

/// On the stairs of a three-storey building (pitched, climbing, bouncing),
/// noise-free points still lie on the mesh.
TEST(SimLidar, NoiseFreeScanOnTheStairsLiesOnTheMesh) {
  const BuildingSpec spec = loadBuildingSpec("default");
  const World world = makeWorld(spec);
  const LidarSimulator lidar(world.building.mesh, world.trajectory, spec.sensors, LidarNoise{}, 1);
  int n = 0;
  for (; n < lidar.scanCount(world.trajectory.duration()); ++n) {
    const FrameKinematics k = world.trajectory.body(lidar.scanStampNs(n) * 1e-9);
    if (k.v_world.z() > 0.1 &&
        std::abs(k.T_world_frame.rotationMatrix()(2, 0)) > std::sin(25 * kDeg))
      break;
  }
  ASSERT_LT(n, lidar.scanCount(world.trajectory.duration())) << "no scan on the stairs";
  const Scan scan = lidar.simulateScan(n);
  ASSERT_GT(scan.points.size(), 15000u);
  EXPECT_LT(worstDistanceToMesh(world, scan, spec.sensors.T_body_lidar, 41), 1e-3);
}

TEST(SimLidar, RangeNoiseAndDropoutsFollowTheSpec) {
  const TinyFixture& f = tiny();
  LidarNoise noise;
  noise.range_sigma = 0.015;
  noise.dropout = 0.05;
  const LidarSimulator perfect(f.world.building.mesh, f.world.trajectory, f.spec.sensors,
                               LidarNoise{}, 1);
  const LidarSimulator noisy(f.world.building.mesh, f.world.trajectory, f.spec.sensors, noise, 1);
  const Scan a = perfect.simulateScan(10), b = noisy.simulateScan(10);  // standing still
  EXPECT_NEAR(1.0 - static_cast<double>(b.points.size()) / a.points.size(), 0.05, 0.01);
  // Match by time and ring; the range error's spread is the configured sigma.
  std::map<std::pair<float, int>, double> range;
  for (const ScanPoint& p : a.points) range[{p.time, p.ring}] = p.p.cast<double>().norm();
  double sum = 0, sum2 = 0;
  int count = 0;
  for (const ScanPoint& p : b.points) {
    const auto it = range.find({p.time, p.ring});
    if (it == range.end()) continue;
    const double e = p.p.cast<double>().norm() - it->second;
    sum += e;
    sum2 += e * e;
    ++count;
  }
  ASSERT_GT(count, 20000);
  EXPECT_NEAR(sum / count, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(sum2 / count), 0.015, 0.0015);
}

TEST(SimLidar, GlassReturnsNothing) {
  TriangleMesh mesh;
  mesh.addBox(Eigen::Vector3d(2.0, -5, -5), Eigen::Vector3d(2.02, 5, 5), Surface::kGlass);
  mesh.addBox(Eigen::Vector3d(6.0, -5, -5), Eigen::Vector3d(6.2, 5, 5), Surface::kWall);
  const RayCaster caster(mesh);
  Eigen::Vector3f origins[16], directions[16];
  RayHit hits[16];
  for (int i = 0; i < 16; ++i) {
    origins[i] = Eigen::Vector3f(0, 0, 0);
    directions[i] = Eigen::Vector3f(1.0f, 0.02f * (i - 8), 0.0f).normalized();
  }
  caster.cast16(origins, directions, 100.0f, hits);
  for (int i = 0; i < 16; ++i) {
    ASSERT_TRUE(std::isfinite(hits[i].distance));
    EXPECT_NEAR(hits[i].distance * directions[i].x(), 6.0, 1e-4);
    EXPECT_EQ(mesh.triangles()[hits[i].triangle].surface, Surface::kWall);
  }
  // Beyond the maximum range: no return.
  caster.cast16(origins, directions, 5.0f, hits);
  for (int i = 0; i < 16; ++i) EXPECT_FALSE(std::isfinite(hits[i].distance));
}

}  // namespace
}  // namespace storey::sim
