// `storey info LOG` run as a program: the table of a test-written Velodyne
// bag, a one-line error with exit status 1 on bad files, and the sensor, spin
// rate and scans of a real Velodyne capture (skipped when the real data,
// ../shared/data/real, is absent).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_storey.h"
#include "unit/io/bag_fixtures.h"
#include "unit/io_pcap/real_data.h"

namespace storey {
namespace {

using test::RunResult;
using test::runStorey;
const auto quoted = test::shellQuoted;

class InfoCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir("info_cli"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string dir_;
};

/// Whether some line of `text` starts with these whitespace-separated words.
::testing::AssertionResult hasRow(const std::string& text, const std::vector<std::string>& words) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    std::vector<std::string> found;
    std::string word;
    while (found.size() < words.size() && in >> word) found.push_back(word);
    if (found == words) return ::testing::AssertionSuccess();
  }
  std::string wanted;
  for (const auto& w : words) wanted += w + " ";
  return ::testing::AssertionFailure() << "no row '" << wanted << "' in:\n" << text;
}

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << part << "' not in:\n" << text;
}

TEST_F(InfoCli, VelodyneBagTable) {
  const std::string bag = dir_ + "/velodyne.bag";
  test::VelodyneImuBag spec;  // 10 scans of 64 points at 10 Hz, IMU at 200 Hz
  spec.scans = 11;
  test::writeVelodyneImuBag(bag, spec);

  const RunResult r = runStorey("info " + quoted(bag), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_TRUE(contains(r.out, bag));
  EXPECT_TRUE(contains(r.out, "ROS1 bag 2.0"));
  // Topics: type, messages, rate [Hz], duration [s], first and last header stamps.
  EXPECT_TRUE(hasRow(r.out, {"topic", "type", "messages", "rate", "Hz", "duration", "s"}));
  EXPECT_TRUE(hasRow(r.out, {"/velodyne_points", "sensor_msgs/PointCloud2", "11", "10.00", "1.000",
                             "1700000000.000000", "1700000001.000000", "header"}));
  EXPECT_TRUE(hasRow(r.out, {"/imu/data", "sensor_msgs/Imu", "220", "200.00", "1.095",
                             "1700000000.000000", "1700000001.095000", "header"}));
  // Fields of the Velodyne layout (name, datatype, offset, count) and points per message.
  EXPECT_TRUE(contains(r.out, "point_step 32"));
  EXPECT_TRUE(contains(r.out, "min 64, median 64, max 64"));
  EXPECT_TRUE(hasRow(r.out, {"field", "datatype", "offset", "count"}));
  EXPECT_TRUE(hasRow(r.out, {"x", "float32", "0", "1"}));
  EXPECT_TRUE(hasRow(r.out, {"y", "float32", "4", "1"}));
  EXPECT_TRUE(hasRow(r.out, {"z", "float32", "8", "1"}));
  EXPECT_TRUE(hasRow(r.out, {"intensity", "float32", "16", "1"}));
  EXPECT_TRUE(hasRow(r.out, {"ring", "uint16", "20", "1"}));
  EXPECT_TRUE(hasRow(r.out, {"time", "float32", "24", "1"}));
  EXPECT_TRUE(
      contains(r.out, "Storey reads the LiDAR from /velodyne_points and IMU from /imu/data"));
}

TEST_F(InfoCli, BadFilesExitOneWithAOneLineMessage) {
  const std::string empty = dir_ + "/empty.bag";
  test::writeFileBytes(empty, "");
  const std::string text = dir_ + "/text.bag";
  test::writeFileBytes(text, "not a bag\n");
  const std::string truncated = dir_ + "/truncated.bag";
  const std::string full = dir_ + "/full.bag";
  test::writeVelodyneImuBag(full, test::VelodyneImuBag{});
  test::truncatedCopy(full, truncated, std::filesystem::file_size(full) / 2);
  const std::string missing = dir_ + "/missing.bag";

  for (const std::string& file : {empty, text, truncated, missing}) {
    const RunResult r = runStorey("info " + quoted(file), dir_);
    EXPECT_EQ(r.exit_code, 1) << file << "\n" << r.out << r.err;
    std::string err = r.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    EXPECT_EQ(err.find('\n'), std::string::npos) << "more than one line:\n" << r.err;
    EXPECT_TRUE(contains(err, file));
  }
}

class PcapInfoCli : public InfoCli {};

TEST_F(PcapInfoCli, ShowsSensorRateAndScans) {
  const std::string pcap =
      test::realData("veloview-vlp16-indoor/vlp-16-test-90deg-1-50-frames.pcap");
  if (!std::filesystem::exists(pcap)) GTEST_SKIP() << "real data absent: " << pcap;
  const RunResult r = runStorey("info " + quoted(pcap), dir_);
  const std::string out = r.out + r.err;
  EXPECT_EQ(r.exit_code, 0) << out;
  EXPECT_TRUE(contains(out, "Velodyne pcap"));
  EXPECT_TRUE(contains(out, "VLP-16"));
  EXPECT_TRUE(contains(out, "rotation     19.9"));
  EXPECT_TRUE(contains(out, "scan        52"));
  EXPECT_TRUE(contains(out, "--imu-csv"));  // no IMU: says how to give one
}

}  // namespace
}  // namespace storey
