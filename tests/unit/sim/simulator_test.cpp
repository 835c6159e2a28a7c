#include "sim/simulator.h"

#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "common/error.h"
#include "config/config.h"
#include "sim/world.h"
#include "support/temp_dir.h"

namespace storey::sim {
namespace {

namespace fs = std::filesystem;

/// A per-process scratch folder, removed when the test program exits.
struct ScratchRoot {
  fs::path path = fs::temp_directory_path() / ("storey_sim_test_" + std::to_string(::getpid()));
  ~ScratchRoot() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

fs::path scratch(const std::string& name) {
  static const ScratchRoot root;
  const fs::path dir = root.path / name;
  fs::remove_all(dir);
  return dir;
}

int countLines(const fs::path& path, bool skip_comments = true) {
  std::ifstream in(path);
  std::string line;
  int n = 0;
  while (std::getline(in, line))
    if (!(skip_comments && !line.empty() && line[0] == '#')) ++n;
  return n;
}

SimulationOptions shortRun() {
  SimulationOptions options;
  options.max_duration = 4.0;
  return options;
}

TEST(SimOutput, BagHasTheVelodyneDriverLayout) {
  const BuildingSpec spec = loadBuildingSpec("tiny");
  const fs::path out = scratch("layout");
  const SimulationResult result = simulate(spec, shortRun(), out.string());
  EXPECT_EQ(result.scans, 40);  // 4 s at 10 Hz
  EXPECT_EQ(result.imu_samples, 4 * 400 + 1);

  rosbag::Bag bag(out / kBagFile, rosbag::bagmode::Read);
  rosbag::View clouds(bag, rosbag::TopicQuery("/velodyne_points"));
  rosbag::View imus(bag, rosbag::TopicQuery("/imu/data"));
  EXPECT_EQ(static_cast<std::int64_t>(clouds.size()), result.scans);
  EXPECT_EQ(static_cast<std::int64_t>(imus.size()), result.imu_samples);
  std::int64_t points = 0;
  ros::Time previous;
  for (const rosbag::MessageInstance& m : clouds) {
    const auto cloud = m.instantiate<sensor_msgs::PointCloud2>();
    ASSERT_TRUE(cloud);
    EXPECT_EQ(cloud->header.frame_id, "velodyne");
    EXPECT_EQ(cloud->height, 1u);
    EXPECT_EQ(cloud->point_step, 32u);
    EXPECT_EQ(cloud->row_step, 32u * cloud->width);
    EXPECT_TRUE(cloud->is_dense);
    EXPECT_FALSE(cloud->is_bigendian);
    ASSERT_EQ(cloud->fields.size(), 6u);
    const std::pair<const char*, std::pair<int, int>> expected[6] = {
        {"x", {0, sensor_msgs::PointField::FLOAT32}},
        {"y", {4, sensor_msgs::PointField::FLOAT32}},
        {"z", {8, sensor_msgs::PointField::FLOAT32}},
        {"intensity", {16, sensor_msgs::PointField::FLOAT32}},
        {"ring", {20, sensor_msgs::PointField::UINT16}},
        {"time", {24, sensor_msgs::PointField::FLOAT32}}};
    for (int i = 0; i < 6; ++i) {
      EXPECT_EQ(cloud->fields[i].name, expected[i].first);
      EXPECT_EQ(static_cast<int>(cloud->fields[i].offset), expected[i].second.first);
      EXPECT_EQ(static_cast<int>(cloud->fields[i].datatype), expected[i].second.second);
      EXPECT_EQ(cloud->fields[i].count, 1u);
    }
    // Stamps: the first firing of the frame's first block as the packets'
    // microsecond clock gives it (1.7e9 s + a multiple of the firing sequence,
    // within 1 us); record time after the stamp.
    const std::int64_t since_start =
        static_cast<std::int64_t>(cloud->header.stamp.toNSec() - 1'700'000'000'000'000'000ULL);
    const std::int64_t off_sequence = (since_start + 27648) % 55296 - 27648;
    EXPECT_LE(std::abs(off_sequence), 1000) << since_start;
    EXPECT_GT(m.getTime(), cloud->header.stamp);
    EXPECT_GT(cloud->header.stamp, previous);
    previous = cloud->header.stamp;
    float last_time = -1.0f;
    for (std::uint32_t i = 0; i < cloud->width; ++i) {
      const std::uint8_t* p = cloud->data.data() + i * 32;
      float x, y, z, time;
      std::uint16_t ring;
      std::memcpy(&x, p, 4);
      std::memcpy(&y, p + 4, 4);
      std::memcpy(&z, p + 8, 4);
      std::memcpy(&ring, p + 20, 2);
      std::memcpy(&time, p + 24, 4);
      ASSERT_LT(ring, 16);
      ASSERT_GE(time, last_time);              // firing order
      ASSERT_LT(time, 0.1f + 2 * 55.296e-6f);  // a revolution, cut at a block of two sequences
      ASSERT_GE(std::sqrt(x * x + y * y + z * z), 0.4f);
      last_time = time;
    }
    points += cloud->width;
  }
  EXPECT_EQ(points, result.points);
  std::uint64_t expected_ns = 1'700'000'000'000'000'000ULL;
  for (const rosbag::MessageInstance& m : imus) {
    const auto imu = m.instantiate<sensor_msgs::Imu>();
    ASSERT_TRUE(imu);
    EXPECT_EQ(imu->header.frame_id, "imu");
    EXPECT_EQ(imu->header.stamp.toNSec(), expected_ns);
    EXPECT_EQ(m.getTime(), imu->header.stamp);
    EXPECT_EQ(imu->orientation_covariance[0], -1.0);
    if (expected_ns < 1'700'000'002'000'000'000ULL) {  // standing still, IMU level: gravity + bias
      EXPECT_NEAR(imu->linear_acceleration.z, 9.81, 0.1);
    }
    expected_ns += 2'500'000;
  }
  bag.close();

  // Ground truth and the other files.
  EXPECT_EQ(countLines(out / kLidarTruthFile), result.scans);
  EXPECT_EQ(countLines(out / kImuTruthFile), result.imu_samples);
  for (const char* name : {kMeshFile, kStoreysFile, kCalibrationFile})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  EXPECT_EQ(
      test::readText((out / kMeshFile).string()).rfind("ply\nformat binary_little_endian 1.0\n", 0),
      0u);
  Config config;
  applyCalibrationFile(config, (out / kCalibrationFile).string());
  EXPECT_TRUE(config.sensor.T_imu_lidar.isApprox(
      spec.sensors.T_body_imu.inverse() * spec.sensors.T_body_lidar, 1e-12, 1e-12));
  EXPECT_DOUBLE_EQ(config.sensor.imu.rate_hz, 400.0);
  EXPECT_EQ(config.input.points_topic, "/velodyne_points");
  // No temporary folder is left next to the output.
  for (const auto& entry : fs::directory_iterator(out.parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST(SimOutput, SameSpecAndSeedGiveTheSameBytes) {
  const BuildingSpec spec = loadBuildingSpec("tiny");
  const fs::path a = scratch("same_a"), b = scratch("same_b");
  SimulationOptions options = shortRun();
  options.threads = 2;
  simulate(spec, options, a.string());
  options.threads = 1;
  simulate(spec, options, b.string());
  int files = 0;
  for (const auto& entry : fs::directory_iterator(a)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(test::readText(entry.path().string()) == test::readText((b / name).string()))
        << name << " differs";
    ++files;
  }
  EXPECT_EQ(files, 7);  // bag, two truths, mesh, storeys, calibration, spec
  // A different seed changes the noise.
  BuildingSpec other = spec;
  other.seed = spec.seed + 1;
  const fs::path c = scratch("same_c");
  simulate(other, shortRun(), c.string());
  EXPECT_FALSE(test::readText((a / kBagFile).string()) == test::readText((c / kBagFile).string()));
}

TEST(SimOutput, StartAtLeavesOutTheLogBeforeIt) {
  // --start-at: the bag and both truths begin at the cut, the rest unchanged.
  const BuildingSpec spec = loadBuildingSpec("tiny");
  const fs::path whole = scratch("cut_whole"), cut = scratch("cut_at");
  simulate(spec, shortRun(), whole.string());
  SimulationOptions options = shortRun();
  options.start_at = 2.5;
  const SimulationResult result = simulate(spec, options, cut.string());
  const double t_cut = spec.sensors.start_time + 2.5;
  rosbag::Bag bag(cut / kBagFile, rosbag::bagmode::Read);
  rosbag::View view(bag);
  int scans = 0, imu = 0;
  for (const rosbag::MessageInstance& m : view) {
    if (const auto cloud = m.instantiate<sensor_msgs::PointCloud2>()) {
      EXPECT_GE(cloud->header.stamp.toSec(), t_cut - 1e-6);
      ++scans;
    } else if (const auto sample = m.instantiate<sensor_msgs::Imu>()) {
      EXPECT_GE(sample->header.stamp.toSec(), t_cut - 1e-6);
      ++imu;
    }
  }
  EXPECT_EQ(scans, result.scans);
  EXPECT_EQ(imu, result.imu_samples);
  // 1.5 s of a 10 Hz LiDAR and a 400 Hz IMU are left, and their truth.
  EXPECT_NEAR(scans, 15, 1);
  EXPECT_NEAR(imu, 600, 2);
  EXPECT_EQ(countLines(cut / kLidarTruthFile), scans);
  EXPECT_EQ(countLines(cut / kImuTruthFile), imu);
  // The truth that is left is the whole log's: the cut log's packets start
  // afresh at the cut, so its stamps may differ by their microsecond rounding.
  std::ifstream a(whole / kLidarTruthFile), b(cut / kLidarTruthFile);
  std::string la, lb;
  std::getline(b, lb);
  std::getline(b, lb);  // the first pose after the header
  const auto numbers = [](const std::string& line) {
    std::istringstream in(line);
    std::vector<double> v(8);
    for (double& x : v) in >> x;
    return v;
  };
  const std::vector<double> first = numbers(lb);
  bool found = false;
  while (std::getline(a, la)) {
    if (la.empty() || la[0] == '#') continue;
    const std::vector<double> pose = numbers(la);
    bool same = std::abs(pose[0] - first[0]) < 1e-6;
    for (int k = 1; k < 8; ++k) same = same && std::abs(pose[k] - first[k]) < 1e-5;
    found = found || same;
  }
  EXPECT_TRUE(found) << lb;
  options.start_at = 4.0;  // nothing left
  EXPECT_THROW(simulate(spec, options, scratch("cut_all").string()), Error);
}

// Simulating again into the same folder replaces its files, the ROS 2 bag's
// folder too (it was "cannot move into place: Directory not empty").
TEST(SimOutput, ASecondSimulationReplacesTheFirstsFiles) {
  const BuildingSpec spec = loadBuildingSpec("tiny");
  const fs::path out = scratch("again");
  SimulationOptions options = shortRun();
  options.max_duration = 1.0;
  options.formats.ros2 = Ros2Format::kDb3;
  simulate(spec, options, out.string());
  options.max_duration = 2.0;
  const SimulationResult second = simulate(spec, options, out.string());
  EXPECT_EQ(second.scans, 20);
  EXPECT_EQ(countLines(out / kLidarTruthFile), 20);
  std::size_t bag_files = 0;
  for (const auto& entry : fs::directory_iterator(out / kRos2BagDir)) {
    (void)entry;
    ++bag_files;
  }
  EXPECT_EQ(bag_files, 2u) << "metadata.yaml and one .db3";
}

TEST(SimOutput, CancelLeavesNoOutput) {
  const fs::path out = scratch("cancel");
  int calls = 0;
  EXPECT_THROW(simulate(loadBuildingSpec("tiny"), shortRun(), out.string(),
                        [&](double, const std::string&) { return ++calls < 3; }),
               Cancelled);
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(out.parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST(SimOutput, StoreysAreInTheWorldFrame) {
  const fs::path out = scratch("storeys");
  SimulationOptions options;
  options.max_duration = 0.5;
  const BuildingSpec spec = loadBuildingSpec("default");
  simulate(spec, options, out.string());
  const std::string text = test::readText((out / kStoreysFile).string());
  // The LiDAR starts at body_height + 0.12 above the ground floor: floor_z = -0.62.
  EXPECT_NE(text.find("floor_z: -0.620000"), std::string::npos) << text;
  EXPECT_NE(text.find("floor_z: 2.780000"), std::string::npos) << text;  // + 3.4
  EXPECT_NE(text.find("floor_z: 5.780000"), std::string::npos) << text;  // + 3.0
}

}  // namespace
}  // namespace storey::sim
