// The same simulated walk (the `tiny` building, 6 s) written as a ROS1 bag, a
// rosbag2 sqlite3 bag, MCAP with none / zstd / lz4 chunks, and with the LiDAR
// as Velodyne packets (ROS1 bag, db3, and the pcap of the same packets):
// `storey run` gives the same trajectory from every container.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

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

/// Largest position difference of two trajectories with the same stamps [m].
double maxDifference(const std::vector<TumLine>& a, const std::vector<TumLine>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    EXPECT_NEAR(a[i].t, b[i].t, 1e-6);
    worst = std::max(
        {worst, std::abs(a[i].x - b[i].x), std::abs(a[i].y - b[i].y), std::abs(a[i].z - b[i].z)});
  }
  return worst;
}

class Ros2Formats : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = std::make_unique<test::TempDir>(); }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::string simulate(const std::string& name, const std::string& flags) {
    const std::string out = dir_->file(name);
    const auto r = runStorey(
        "simulate tiny --duration 6 --threads 2 --no-progress -o " + shellQuoted(out) + " " + flags,
        dir_->path().string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
  }
  /// Runs `storey run LOG` with the simulation's calibration; the trajectory.
  static std::vector<TumLine> run(const std::string& sim, const std::string& log,
                                  const std::string& name, const std::string& extra = "") {
    const std::string out = dir_->file(name);
    const auto r =
        runStorey("run " + shellQuoted(log) + " -o " + shellQuoted(out) + " --calibration " +
                      shellQuoted(sim + "/calibration.yaml") + " --no-render " + extra,
                  dir_->path().string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return readTum(out + "/trajectory.tum");
  }
  static inline std::unique_ptr<test::TempDir> dir_;
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
  // The packet frames start where the azimuth wraps: their own ground truth.
  const auto truth = readTum(sim + "/" + sim::kPcapLidarTruthFile);
  ASSERT_FALSE(truth.empty());
  int stamped = 0;
  for (const auto& pose : from_bag) {
    for (const auto& t : truth) stamped += std::abs(t.t - pose.t) < 1e-5;
  }
  EXPECT_EQ(stamped, static_cast<int>(from_bag.size()));
}

}  // namespace
}  // namespace storey
