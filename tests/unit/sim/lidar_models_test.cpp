// The simulated LiDAR models against their published tables and timing, and
// a scan of each (mounted pitched and yawed) against the true mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "common/error.h"
#include "io/velodyne/velodyne_tables.h"
#include "sim/lidar_model.h"
#include "sim/lidar_simulator.h"
#include "sim/vlp16.h"
#include "sim/world.h"
#include "unit/sim/scan_on_mesh.h"

namespace storey::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Published tables, typed in from the manuals (laser id order), not from the code.
// VLP-16 User Manual 63-9243, "Vertical Angles".
constexpr double kVlp16Deg[16] = {-15, 1, -13, 3, -11, 5, -9, 7, -7, 9, -5, 11, -3, 13, -1, 15};
// VLP-32C User Manual 63-9325, vertical angle and azimuth offset per laser id.
constexpr double kVlp32cDeg[32] = {-25,    -1,    -1.667, -15.639, -11.31, 0,     -0.667, -8.843,
                                   -7.254, 0.333, -0.333, -6.148,  -5.333, 1.333, 0.667,  -4,
                                   -4.667, 1.667, 1,      -3.667,  -3.333, 3.333, 2.333,  -2.667,
                                   -3,     7,     4.667,  -2.333,  -2,     15,    10.333, -1.333};
constexpr double kVlp32cAzimuthDeg[32] = {
    1.4, -4.2, 1.4, -1.4, 1.4, -1.4, 4.2, -1.4, 1.4, -4.2, 1.4, -1.4, 4.2, -1.4, 4.2, -1.4,
    1.4, -4.2, 1.4, -4.2, 4.2, -1.4, 1.4, -1.4, 1.4, -1.4, 1.4, -4.2, 4.2, -1.4, 1.4, -1.4};
// HDL-32E User's Manual 63-9113, Appendix A: even ids -30.67 up in 4/3 deg
// steps, odd ids -9.33 up in 4/3 deg steps, printed with two decimals.
double hdl32eDeg(int id) {
  const double thirds = (id % 2 == 0 ? -92.0 : -28.0) + 4.0 * (id / 2);  // in 1/3 deg
  return std::round(thirds / 3.0 * 100.0) / 100.0;
}

void expectRingsRankElevations(const LidarBeams& beams) {
  std::vector<int> order(beams.channels());
  for (int c = 0; c < beams.channels(); ++c) order[c] = c;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return beams.elevation[a] < beams.elevation[b]; });
  for (int rank = 0; rank < beams.channels(); ++rank)
    EXPECT_EQ(beams.ring[order[rank]], rank) << toString(beams.model);
}

TEST(SimLidar, Vlp16TableAndTimingAreTheManuals) {
  const LidarBeams beams = lidarBeams(LidarModel::kVlp16);
  ASSERT_EQ(beams.channels(), 16);
  EXPECT_EQ(beams.layout, CloudLayout::kVelodyne);
  EXPECT_EQ(beams.sequence_period_ns, 55296);
  EXPECT_DOUBLE_EQ(beams.distance_step, 0.002);
  for (int id = 0; id < 16; ++id) {
    EXPECT_NEAR(beams.elevation[id], kVlp16Deg[id] * kDeg, 1e-12);
    EXPECT_EQ(beams.elevation[id], vlp16::elevation(id));  // sim/vlp16.h's table
    EXPECT_EQ(beams.ring[id], vlp16::ring(id));
    EXPECT_EQ(beams.firing_ns[id], id * 2304);
    EXPECT_EQ(beams.azimuth_offset[id], 0.0);
  }
  expectRingsRankElevations(beams);
}

TEST(SimLidar, Vlp32cTableAndTimingAreTheManuals) {
  const LidarBeams beams = lidarBeams(LidarModel::kVlp32c);
  const velodyne::Calibration decoder = velodyne::defaultCalibration(velodyne::Model::kVlp32c);
  ASSERT_EQ(beams.channels(), 32);
  ASSERT_EQ(decoder.lasers.size(), 32u);
  EXPECT_EQ(beams.sequence_period_ns, 55296);  // 12 blocks of one sequence per packet
  EXPECT_DOUBLE_EQ(beams.distance_step, 0.004);
  EXPECT_DOUBLE_EQ(decoder.distance_resolution_m, 0.004);
  std::set<double> distinct;
  for (int id = 0; id < 32; ++id) {
    EXPECT_NEAR(beams.elevation[id], kVlp32cDeg[id] * kDeg, 1e-12) << id;
    EXPECT_NEAR(beams.azimuth_offset[id], kVlp32cAzimuthDeg[id] * kDeg, 1e-12) << id;
    // The decoder's table: same elevation, its rotational correction subtracted.
    EXPECT_NEAR(decoder.lasers[id].elevation_deg, kVlp32cDeg[id], 1e-12) << id;
    EXPECT_NEAR(decoder.lasers[id].azimuth_offset_deg, -kVlp32cAzimuthDeg[id], 1e-12) << id;
    EXPECT_EQ(beams.ring[id], decoder.lasers[id].ring) << id;
    // Lasers fire in pairs (2k, 2k + 1) every 2.304 us: 16 firings + 8 idle slots.
    EXPECT_EQ(beams.firing_ns[id], (id / 2) * 2304) << id;
    EXPECT_NEAR(velodyne::laserFiringOffset(velodyne::Model::kVlp32c, id), (id / 2) * 2.304e-6,
                1e-15);
    distinct.insert(kVlp32cDeg[id]);
  }
  EXPECT_EQ(distinct.size(), 32u);
  EXPECT_EQ(*distinct.begin(), -25.0);
  EXPECT_EQ(*distinct.rbegin(), 15.0);
  // Uneven: 0.333 deg apart around the horizon, 4.333 deg near the top.
  EXPECT_NEAR(beams.elevation[9] - beams.elevation[5], 0.333 * kDeg, 1e-9);
  expectRingsRankElevations(beams);
}

TEST(SimLidar, Hdl32eTableAndTimingAreTheManuals) {
  const LidarBeams beams = lidarBeams(LidarModel::kHdl32e);
  const velodyne::Calibration decoder = velodyne::defaultCalibration(velodyne::Model::kHdl32e);
  ASSERT_EQ(beams.channels(), 32);
  EXPECT_EQ(beams.sequence_period_ns, 46080);  // 40 slots of 1.152 us
  EXPECT_DOUBLE_EQ(beams.distance_step, 0.002);
  for (int id = 0; id < 32; ++id) {
    EXPECT_NEAR(beams.elevation[id], hdl32eDeg(id) * kDeg, 1e-12) << id;
    EXPECT_NEAR(beams.elevation[id], decoder.lasers[id].elevation_deg * kDeg, 1e-12) << id;
    EXPECT_EQ(beams.ring[id], decoder.lasers[id].ring);
    EXPECT_EQ(beams.firing_ns[id], id * 1152) << id;
  }
  EXPECT_NEAR(*std::min_element(beams.elevation.begin(), beams.elevation.end()), -30.67 * kDeg,
              1e-12);
  EXPECT_NEAR(*std::max_element(beams.elevation.begin(), beams.elevation.end()), 10.67 * kDeg,
              1e-12);
  expectRingsRankElevations(beams);
}

TEST(SimLidar, Os1_64IsUniformAndFiresColumns) {
  const LidarBeams beams = lidarBeams(LidarModel::kOs1_64);
  ASSERT_EQ(beams.channels(), 64);
  EXPECT_EQ(beams.layout, CloudLayout::kOuster);
  EXPECT_EQ(beams.columns, 1024);
  EXPECT_EQ(beams.sequence_period_ns, 0);
  EXPECT_DOUBLE_EQ(beams.distance_step, 0.001);
  for (int row = 0; row < 64; ++row) {
    EXPECT_NEAR(beams.elevation[row], (22.5 - row * 45.0 / 63.0) * kDeg, 1e-12);  // row 0 on top
    EXPECT_EQ(beams.firing_ns[row], 0);  // a column fires every beam at once
    EXPECT_EQ(beams.azimuth_offset[row], 0.0);
    EXPECT_EQ(beams.ring[row], 63 - row);  // Storey's rings count from the lowest beam
  }
  expectRingsRankElevations(beams);
  EXPECT_THROW(lidarBeams(LidarModel::kGeneric), Error);
}

struct ModelCase {
  LidarModel model;
  int sequences_min, sequences_max;  ///< firing sequences (columns) per 10 Hz scan
};

/// A noise-free scan of each model, the LiDAR pitched down 20 deg and turned
/// 90 deg to the left on the body: timing, rings and every point on the mesh
/// when placed with the true pose at its own time.
TEST(SimLidar, EveryModelScansTheMeshFromAPitchedYawedMount) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.sensors.T_body_lidar =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(90 * kDeg, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(20 * kDeg, Eigen::Vector3d::UnitY())),
           Eigen::Vector3d(0.2, 0.05, 0.15));
  for (const ModelCase& m :
       {ModelCase{LidarModel::kVlp16, 1808, 1809}, ModelCase{LidarModel::kVlp32c, 1808, 1809},
        ModelCase{LidarModel::kHdl32e, 2170, 2171}, ModelCase{LidarModel::kOs1_64, 1024, 1024}}) {
    SCOPED_TRACE(toString(m.model));
    spec.sensors.lidar.model = m.model;
    const World world = makeWorld(spec);
    const LidarSimulator lidar(world.building.mesh, world.trajectory, spec.sensors, LidarNoise{},
                               1);
    const LidarBeams& beams = lidar.beams();
    const int n = 60;  // walking
    ASSERT_GT(world.trajectory.body(lidar.scanStampNs(n) * 1e-9).v_world.norm(), 0.3);
    OrganisedScan organised;
    const Scan scan = lidar.simulateScan(n, nullptr, &organised);
    EXPECT_GE(organised.columns, m.sequences_min);
    EXPECT_LE(organised.columns, m.sequences_max);
    EXPECT_EQ(organised.rows, beams.channels());
    EXPECT_GE(scan.stamp_ns, n * 100'000'000LL);
    EXPECT_GT(scan.points.size(), organised.cells.size() / 2);  // indoors most beams return
    std::map<std::uint16_t, double> ring_elevation;
    for (int c = 0; c < beams.channels(); ++c) ring_elevation[beams.ring[c]] = beams.elevation[c];
    ASSERT_EQ(ring_elevation.size(), static_cast<std::size_t>(beams.channels()));
    const double period =
        beams.sequence_period_ns > 0 ? beams.sequence_period_ns * 1e-9 : 0.1 / beams.columns;
    for (const ScanPoint& p : scan.points) {
      ASSERT_GE(p.time, 0.0f);
      ASSERT_LT(p.time, 0.1 + 40e-6);  // the last sequence's lasers may fire after 0.1 s
      const double elevation = std::atan2(p.p.z(), std::hypot(p.p.x(), p.p.y()));
      ASSERT_NEAR(elevation, ring_elevation.at(p.ring), 2e-6);
      // Fired at its sequence's start plus its laser's offset.
      // (float times: a few ns off; 100 ns of slack keeps a sequence start at 0)
      const double within = std::fmod(p.time + 1e-7, period) - 1e-7;
      const auto c = std::find(beams.ring.begin(), beams.ring.end(), p.ring) - beams.ring.begin();
      ASSERT_NEAR(within, beams.firing_ns[c] * 1e-9, 2e-8) << "ring " << p.ring;
    }
    EXPECT_LT(worstDistanceToMesh(world, scan, spec.sensors.T_body_lidar, 37), 1e-3);
    // The organised cells hold the same returns, a column's time in every cell.
    std::size_t returns = 0;
    for (int row = 0; row < organised.rows; ++row) {
      for (int col = 0; col < organised.columns; ++col) {
        const OrganisedPoint& cell = organised.at(row, col);
        ASSERT_EQ(cell.t_ns, organised.at(0, col).t_ns);
        if (cell.range_mm == 0) {
          ASSERT_EQ(cell.p, Eigen::Vector3f::Zero());
          continue;
        }
        ++returns;
        ASSERT_NEAR(cell.p.norm(), cell.range_mm * 1e-3, 6e-4);
      }
    }
    EXPECT_EQ(returns, scan.points.size());
  }
}

/// Ouster columns: 1024 per revolution, scan n starts at exactly n / rate.
TEST(SimLidar, Os1_64ColumnsDivideTheRevolution) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.sensors.lidar.model = LidarModel::kOs1_64;
  const World world = makeWorld(spec);
  const LidarSimulator lidar(world.building.mesh, world.trajectory, spec.sensors, LidarNoise{}, 1);
  for (int n : {0, 1, 7, 100}) {
    EXPECT_EQ(lidar.scanStampNs(n), n * 100'000'000LL);
    EXPECT_EQ(lidar.scanEndNs(n), n * 100'000'000LL + 99'902'344LL);  // column 1023: 1023/10240 s
  }
  EXPECT_EQ(lidar.scanCount(10.0), 100);
  OrganisedScan organised;
  lidar.simulateScan(3, nullptr, &organised);
  ASSERT_EQ(organised.columns, 1024);
  for (int col = 0; col < 1024; ++col)
    EXPECT_EQ(organised.at(0, col).t_ns, (col * 100'000'000LL + 512) / 1024);
}

TEST(SimLidar, VelodynePacketsAreForVelodyneModelsOnly) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.sensors.lidar.model = LidarModel::kOs1_64;
  const World world = makeWorld(spec);
  const LidarSimulator lidar(world.building.mesh, world.trajectory, spec.sensors, LidarNoise{}, 1);
  std::vector<VelodyneFiring> firings;
  EXPECT_THROW(lidar.simulateScan(0, &firings), Error);
}

}  // namespace
}  // namespace storey::sim
