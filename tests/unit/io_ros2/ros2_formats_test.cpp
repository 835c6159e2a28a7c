// The same simulated walk (the `tiny` building, 6 s) written as a ROS1 bag, a
// rosbag2 sqlite3 bag, MCAP with none / zstd / lz4 chunks, and with the LiDAR
// as Velodyne packets (ROS1 bag, db3, and the pcap of the same packets):
// `storey run` gives the same trajectory from every container; the packets,
// cut at the clouds' azimuth, decode into the clouds' scans, point for point.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <variant>

#include "config/config.h"
#include "io/log_reader.h"
#include "sim/simulator.h"
#include "support/run_storey.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

using test::runStorey;
using test::shellQuoted;

struct TumLine {
  double t, x, y, z;
};

std::vector<TumLine> readTum(const std::string& path) {
  std::vector<TumLine> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    TumLine l;
    words >> l.t >> l.x >> l.y >> l.z;
    out.push_back(l);
  }
  return out;
}

/// Largest position difference (per axis) of two trajectories with the same
/// stamps (within `stamp_tolerance` [s]) [m].
double maxDifference(const std::vector<TumLine>& a, const std::vector<TumLine>& b,
                     double stamp_tolerance = 1e-6) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    EXPECT_NEAR(a[i].t, b[i].t, stamp_tolerance);
    worst = std::max(
        {worst, std::abs(a[i].x - b[i].x), std::abs(a[i].y - b[i].y), std::abs(a[i].z - b[i].z)});
  }
  return worst;
}

/// Every scan of a log, read with a simulation's calibration.
std::vector<Scan> readScans(const std::string& log, const std::string& calibration) {
  Config config;
  applyCalibrationFile(config, calibration);
  const auto reader = openLog(log, config.input, config.sensor);
  std::vector<Scan> scans;
  LogMessage message;
  while (reader->next(message)) {
    if (auto* scan = std::get_if<Scan>(&message)) scans.push_back(std::move(*scan));
  }
  return scans;
}

class Ros2Formats : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = std::make_unique<test::TempDir>(); }
  static void TearDownTestSuite() {
    dir_.reset();
    simulated_.clear();
  }

  /// Simulates `tiny` (6 s) into `name` once per suite.
  static std::string simulate(const std::string& name, const std::string& flags) {
    const std::string out = dir_->file(name);
    if (simulated_.count(name) != 0) return out;
    const auto r = runStorey(
        "simulate tiny --duration 6 --threads 2 --no-progress -o " + shellQuoted(out) + " " + flags,
        dir_->path().string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    simulated_[name] = flags;
    return out;
  }
  /// Runs `storey run LOG` with the simulation's calibration; the trajectory
  /// (or another of the run's TUM files).
  static std::vector<TumLine> run(const std::string& sim, const std::string& log,
                                  const std::string& name, const std::string& extra = "",
                                  std::vector<TumLine>* odometry = nullptr) {
    const std::string out = dir_->file(name);
    const auto r =
        runStorey("run " + shellQuoted(log) + " -o " + shellQuoted(out) + " --calibration " +
                      shellQuoted(sim + "/calibration.yaml") + " --no-render " + extra,
                  dir_->path().string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    if (odometry != nullptr) *odometry = readTum(out + "/odometry.tum");
    return readTum(out + "/trajectory.tum");
  }
  static inline std::unique_ptr<test::TempDir> dir_;
  static inline std::map<std::string, std::string> simulated_;
};

TEST_F(Ros2Formats, PointCloudsGiveTheSameTrajectoryFromEveryContainer) {
  const std::string db3 = simulate("db3", "--ros2 db3");
  const auto reference = run(db3, db3 + "/simulation.bag", "run_ros1");
  ASSERT_GT(reference.size(), 40u);
  const auto from_db3 = run(db3, db3 + "/" + sim::kRos2BagDir, "run_db3");
  const double d_db3 = maxDifference(reference, from_db3);
  std::printf("[ formats ] ROS1 bag vs db3: %zu poses, max difference %.6f m\n", reference.size(),
              d_db3);
  EXPECT_LT(d_db3, 1e-3);
  for (const std::string compression : {"none", "zstd", "lz4"}) {
    const std::string mcap =
        simulate("mcap_" + compression, "--no-bag --ros2 mcap --compression " + compression);
    const std::string file = mcap + "/" + sim::kRos2BagDir + "/" + sim::kRos2BagDir + "_0.mcap";
    const auto from_mcap = run(mcap, file, "run_mcap_" + compression);
    const double d = maxDifference(reference, from_mcap);
    std::printf("[ formats ] ROS1 bag vs MCAP (%s): max difference %.6f m\n", compression.c_str(),
                d);
    EXPECT_LT(d, 1e-3) << compression;
  }
}

TEST_F(Ros2Formats, VelodynePacketsGiveTheSameTrajectoryAsTheCapture) {
  const std::string sim = simulate("packets", "--packets --pcap --ros2 db3");
  const auto from_pcap =
      run(sim, sim + "/simulation.pcap", "run_pcap", "--imu-csv " + shellQuoted(sim + "/imu.csv"));
  ASSERT_GT(from_pcap.size(), 40u);
  const auto from_bag = run(sim, sim + "/simulation.bag", "run_packets_ros1");
  const auto from_db3 = run(sim, sim + "/" + sim::kRos2BagDir, "run_packets_db3");
  const double d_bag = maxDifference(from_pcap, from_bag);
  const double d_db3 = maxDifference(from_pcap, from_db3);
  std::printf(
      "[ formats ] pcap vs packets in ROS1 bag: %zu poses, max difference %.6f m; vs "
      "packets in db3: %.6f m\n",
      from_pcap.size(), d_bag, d_db3);
  EXPECT_LT(d_bag, 1e-3);
  EXPECT_LT(d_db3, 1e-3);
  // The packet frames start at the calibration's cut angle (180 deg), a
  // block away from the clouds' scans at most: their own ground truth.
  const auto truth = readTum(sim + "/" + sim::kPcapLidarTruthFile);
  ASSERT_FALSE(truth.empty());
  int stamped = 0;
  for (const auto& pose : from_bag) {
    for (const auto& t : truth) stamped += std::abs(t.t - pose.t) < 1e-5;
  }
  EXPECT_EQ(stamped, static_cast<int>(from_bag.size()));
}

/// Whether two scans carry the same points, bit for bit.
bool samePoints(const Scan& a, const Scan& b) {
  if (a.points.size() != b.points.size()) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const ScanPoint& p = a.points[i];
    const ScanPoint& q = b.points[i];
    if (p.p != q.p || p.intensity != q.intensity || p.time != q.time || p.ring != q.ring)
      return false;
  }
  return true;
}

// A point-cloud bag of a Velodyne holds what the driver decodes from the
// sensor's packets (sim/velodyne_scan_stream.h), as a real one does: the
// packet bags of the same walk (cut at the clouds' azimuth, calibration.yaml's
// lidar.cut_angle_deg: 180 deg) decode into the clouds' scans point for
// point, and `storey run` gives the same trajectory from both (the issue's
// bound: 1 mm).
TEST_F(Ros2Formats, VelodynePacketsCutAtTheCloudsAzimuthAreTheCloudScans) {
  const std::string clouds = simulate("db3", "--ros2 db3");
  const std::string packets = simulate("packets", "--packets --pcap --ros2 db3");
  const auto scans = readScans(clouds + "/simulation.bag", clouds + "/calibration.yaml");
  const auto frames = readScans(packets + "/simulation.bag", packets + "/calibration.yaml");
  ASSERT_EQ(frames.size(), scans.size());
  ASSERT_GT(scans.size(), 50u);
  std::size_t same = 0;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    EXPECT_EQ(frames[i].stamp_ns, scans[i].stamp_ns) << "scan " << i;
    same += samePoints(frames[i], scans[i]);
  }
  EXPECT_EQ(same, scans.size()) << "packet frames with the cloud scan's points, bit for bit";
  // The clouds' ground truth is at their stamps, the packet frames'.
  const auto truth = readTum(clouds + "/" + sim::kLidarTruthFile);
  ASSERT_EQ(truth.size(), scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i)
    EXPECT_NEAR(truth[i].t, nsToSeconds(scans[i].stamp_ns), 1e-6) << "scan " << i;

  std::vector<TumLine> odometry_clouds;
  const auto from_clouds =
      run(clouds, clouds + "/simulation.bag", "cut_clouds", "", &odometry_clouds);
  ASSERT_GT(from_clouds.size(), 40u);
  const std::pair<const char*, std::string> logs[] = {{"ROS1", packets + "/simulation.bag"},
                                                      {"db3", packets + "/" + sim::kRos2BagDir}};
  for (const auto& [label, log] : logs) {
    std::vector<TumLine> odometry_packets;
    const auto from_packets =
        run(packets, log, std::string("cut_packets_") + label, "", &odometry_packets);
    const double odometry = maxDifference(odometry_clouds, odometry_packets);
    const double trajectory = maxDifference(from_clouds, from_packets);
    std::printf(
        "[ formats ] clouds vs packets (%s): %zu poses; odometry max difference %.6f m, "
        "trajectory %.6f m\n",
        label, from_clouds.size(), odometry, trajectory);
    EXPECT_LT(odometry, 1e-3) << label;
    EXPECT_LT(trajectory, 1e-3) << label;
  }
}

}  // namespace
}  // namespace storey
