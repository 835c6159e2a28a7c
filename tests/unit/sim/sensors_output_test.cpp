// What `storey simulate` writes for the other sensor rigs: the Ouster
// driver's organised cloud (its bytes, and Storey's own reader decoding it),
// the IMU's orientation field, the model in calibration.yaml.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <tuple>

#include "common/error.h"
#include "config/config.h"
#include "eval/association.h"
#include "eval/ate.h"
#include "io/log_reader.h"
#include "pipeline/pipeline.h"
#include "sim/imu_simulator.h"
#include "sim/lidar_simulator.h"
#include "sim/simulator.h"
#include "sim/world.h"
#include "support/temp_dir.h"
#include "trajectory/tum.h"

namespace storey::sim {
namespace {

namespace fs = std::filesystem;

template <typename T>
T read(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

bool byRingThenTime(const ScanPoint& a, const ScanPoint& b) {
  return std::tie(a.ring, a.time) < std::tie(b.ring, b.time);
}

/// The organised cloud has the ouster-ros layout, and Storey's reader turns
/// it back into exactly the simulator's returns (rings from the lowest beam).
TEST(SimOutput, OusterCloudHasTheDriverLayoutAndReadsBack) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.sensors.lidar.model = LidarModel::kOs1_64;
  spec.sensors.points_topic = "/ouster/points";
  spec.sensors.lidar_frame_id = "os_sensor";
  SimulationOptions options;
  options.max_duration = 1.0;
  options.perfect_sensors = true;
  const test::TempDir dir;
  const fs::path out = dir.path() / "ouster";
  const SimulationResult result = simulate(spec, options, out.string());
  ASSERT_EQ(result.scans, 10);  // the 10th's last column fires at 0.99990 s

  // The bytes.
  rosbag::Bag bag((out / kBagFile).string(), rosbag::bagmode::Read);
  rosbag::View clouds(bag, rosbag::TopicQuery("/ouster/points"));
  ASSERT_EQ(static_cast<std::int64_t>(clouds.size()), result.scans);
  const std::tuple<const char*, std::uint32_t, std::uint8_t> fields[] = {
      {"x", 0, sensor_msgs::PointField::FLOAT32},
      {"y", 4, sensor_msgs::PointField::FLOAT32},
      {"z", 8, sensor_msgs::PointField::FLOAT32},
      {"intensity", 16, sensor_msgs::PointField::FLOAT32},
      {"t", 20, sensor_msgs::PointField::UINT32},
      {"reflectivity", 24, sensor_msgs::PointField::UINT16},
      {"ring", 26, sensor_msgs::PointField::UINT16},
      {"ambient", 28, sensor_msgs::PointField::UINT16},
      {"range", 32, sensor_msgs::PointField::UINT32}};
  std::int64_t returns = 0;
  std::uint64_t expected_stamp = 1'700'000'000'000'000'000ULL;
  for (const rosbag::MessageInstance& m : clouds) {
    const auto cloud = m.instantiate<sensor_msgs::PointCloud2>();
    ASSERT_TRUE(cloud);
    EXPECT_EQ(cloud->header.frame_id, "os_sensor");
    EXPECT_EQ(cloud->header.stamp.toNSec(), expected_stamp);  // the scan's first column
    expected_stamp += 100'000'000ULL;
    EXPECT_GT(m.getTime(), cloud->header.stamp);
    EXPECT_EQ(cloud->height, 64u);
    EXPECT_EQ(cloud->width, 1024u);
    EXPECT_EQ(cloud->point_step, 48u);
    EXPECT_EQ(cloud->row_step, 48u * 1024u);
    EXPECT_EQ(cloud->data.size(), 48u * 1024u * 64u);
    EXPECT_FALSE(cloud->is_bigendian);
    EXPECT_TRUE(cloud->is_dense);
    ASSERT_EQ(cloud->fields.size(), 9u);
    for (std::size_t i = 0; i < 9; ++i) {
      EXPECT_EQ(cloud->fields[i].name, std::get<0>(fields[i]));
      EXPECT_EQ(cloud->fields[i].offset, std::get<1>(fields[i]));
      EXPECT_EQ(cloud->fields[i].datatype, std::get<2>(fields[i]));
      EXPECT_EQ(cloud->fields[i].count, 1u);
    }
    for (std::uint32_t row = 0; row < 64; ++row) {
      for (std::uint32_t col = 0; col < 1024; ++col) {
        const std::uint8_t* p = cloud->data.data() + row * cloud->row_step + col * 48;
        ASSERT_EQ(read<std::uint16_t>(p + 26), row);  // ring = row, 0 = the top beam
        ASSERT_EQ(read<std::uint32_t>(p + 20), (col * 100'000'000ULL + 512) / 1024);  // t [ns]
        ASSERT_EQ(read<std::uint16_t>(p + 28), 0);                                    // ambient
        const std::uint32_t range = read<std::uint32_t>(p + 32);
        const Eigen::Vector3f xyz(read<float>(p), read<float>(p + 4), read<float>(p + 8));
        if (range == 0) {  // a no-return: a zero point, kept in place
          ASSERT_EQ(xyz, Eigen::Vector3f::Zero());
          ASSERT_EQ(read<float>(p + 16), 0.0f);
          continue;
        }
        ++returns;
        ASSERT_NEAR(xyz.norm() * 1000.0f, static_cast<float>(range), 0.6f);
        ASSERT_GT(read<std::uint16_t>(p + 24), 0);  // reflectivity
        // Row 0 looks 22.5 deg up, row 63 22.5 deg down.
        const double elevation = std::atan2(xyz.z(), std::hypot(xyz.x(), xyz.y())) * 180 / M_PI;
        ASSERT_NEAR(elevation, 22.5 - row * 45.0 / 63.0, 1e-3);
      }
    }
  }
  EXPECT_EQ(returns, result.points);
  bag.close();

  // Storey's reader (as `storey run` opens it) on the calibration written beside the bag.
  Config config;
  applyCalibrationFile(config, (out / kCalibrationFile).string());
  EXPECT_EQ(config.sensor.lidar_model, LidarModel::kOs1_64);
  EXPECT_EQ(config.input.points_topic, "/ouster/points");
  std::unique_ptr<LogReader> reader =
      openLog((out / kBagFile).string(), config.input, config.sensor);
  const World world = makeWorld(spec);
  const LidarSimulator lidar(world.building.mesh, world.trajectory, spec.sensors, LidarNoise{},
                             spec.seed);
  LogMessage message;
  int scans = 0;
  while (reader->next(message)) {
    if (!std::holds_alternative<Scan>(message)) continue;
    Scan decoded = std::get<Scan>(message);
    Scan truth = lidar.simulateScan(scans);
    EXPECT_EQ(decoded.stamp_ns, truth.stamp_ns + 1'700'000'000'000'000'000LL);
    ASSERT_EQ(decoded.points.size(), truth.points.size()) << "scan " << scans;
    std::sort(decoded.points.begin(), decoded.points.end(), byRingThenTime);
    std::sort(truth.points.begin(), truth.points.end(), byRingThenTime);
    for (std::size_t i = 0; i < truth.points.size(); ++i) {
      const ScanPoint& a = decoded.points[i];
      const ScanPoint& b = truth.points[i];
      ASSERT_EQ(a.ring, b.ring) << i;
      ASSERT_EQ(a.time, b.time) << i;
      ASSERT_EQ(a.p, b.p) << i;
      ASSERT_EQ(a.intensity, b.intensity) << i;
    }
    ++scans;
  }
  EXPECT_EQ(scans, result.scans);
}

/// `sensors.imu.orientation: true` fills sensor_msgs/Imu's orientation with the
/// true one and its covariance; calibration.yaml names the LiDAR model.
TEST(SimOutput, ImuOrientationAndLidarModelAreWritten) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.sensors.lidar.model = LidarModel::kVlp32c;
  spec.sensors.imu = imuGrade(ImuGrade::kConsumer, 200.0);
  spec.sensors.imu.orientation = true;
  spec.sensors.T_body_imu =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -2, 0.5).normalized())),
           Eigen::Vector3d(0.1, -0.2, 0.15));
  SimulationOptions options;
  options.max_duration = 3.0;
  const test::TempDir dir;
  const fs::path out = dir.path() / "orientation";
  const SimulationResult result = simulate(spec, options, out.string());
  const ImuSimulation truth =
      simulateImu(makeWorld(spec).trajectory, spec.sensors, result.duration, false, spec.seed);
  rosbag::Bag bag((out / kBagFile).string(), rosbag::bagmode::Read);
  rosbag::View imus(bag, rosbag::TopicQuery("/imu/data"));
  ASSERT_EQ(imus.size(), truth.samples.size());
  ASSERT_EQ(result.imu_samples, 3 * 200 + 1);
  std::size_t i = 0;
  for (const rosbag::MessageInstance& m : imus) {
    const auto imu = m.instantiate<sensor_msgs::Imu>();
    ASSERT_TRUE(imu);
    const Eigen::Quaterniond q(imu->orientation.w, imu->orientation.x, imu->orientation.y,
                               imu->orientation.z);
    EXPECT_LT(q.angularDistance(truth.T_world_imu[i].rotation()), 1e-12);
    for (int a = 0; a < 3; ++a) {
      EXPECT_DOUBLE_EQ(imu->orientation_covariance[4 * a],
                       std::pow(spec.sensors.imu.orientation_sigma[a], 2));
    }
    EXPECT_EQ(imu->orientation_covariance[1], 0.0);
    EXPECT_NEAR(imu->angular_velocity_covariance[0], std::pow(0.014 * M_PI / 180, 2) * 200.0,
                1e-15);
    ++i;
  }
  bag.close();
  Config config;
  applyCalibrationFile(config, (out / kCalibrationFile).string());
  EXPECT_EQ(config.sensor.lidar_model, LidarModel::kVlp32c);
  EXPECT_DOUBLE_EQ(config.sensor.imu.rate_hz, 200.0);
  EXPECT_DOUBLE_EQ(config.sensor.imu.gyro_noise_density, spec.sensors.imu.gyro_noise_density);
  EXPECT_TRUE(config.sensor.T_imu_lidar.isApprox(
      spec.sensors.T_body_imu.inverse() * spec.sensors.T_body_lidar, 1e-12, 1e-12));
}

/// A person carrying a VLP-32C pitched 20 deg down and turned 90 deg left,
/// a consumer IMU 0.3 m away upside down: the world frame is the LiDAR's
/// first heading, as Storey's odometry sets it, and `storey run`'s pipeline
/// follows the truth without alignment.
TEST(SimOutput, PipelineFollowsAHandheldPitchedYawedRig) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.robot = robotForMotion(RobotMotion::kHandheld);
  spec.robot.start_offset = 2.3;  // as the preset
  spec.sensors.lidar.model = LidarModel::kVlp32c;
  spec.sensors.imu = imuGrade(ImuGrade::kConsumer, 200.0);
  const double deg = M_PI / 180.0;
  spec.sensors.T_body_lidar =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(90 * deg, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(20 * deg, Eigen::Vector3d::UnitY())),
           Eigen::Vector3d(0.1, 0.0, 0.2));
  spec.sensors.T_body_imu =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(45 * deg, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX())),
           Eigen::Vector3d(0.3, 0.0, 0.0));
  const World world = makeWorld(spec);
  const Pose T_world_lidar0 = world.trajectory.frame(0.0, spec.sensors.T_body_lidar).T_world_frame;
  EXPECT_LT(T_world_lidar0.translation().norm(), 1e-12);
  const Eigen::Vector3d lidar_x = T_world_lidar0.rotationMatrix().col(0);
  EXPECT_NEAR(std::atan2(lidar_x.y(), lidar_x.x()), 0.0, 1e-12);  // heading +x
  EXPECT_NEAR(lidar_x.z(), -std::sin(20 * deg), 1e-12);           // pitched down

  const test::TempDir dir;
  const fs::path out = dir.path() / "rig";
  const SimulationResult result = simulate(spec, SimulationOptions{}, out.string());
  Config config;
  applyCalibrationFile(config, (out / kCalibrationFile).string());
  const PipelineResult run = runPipeline((out / kBagFile).string(), config, (out / "run").string());
  const storey::Trajectory truth = readTum((out / kLidarTruthFile).string());
  const auto matches = eval::associate(truth, run.trajectory);
  const double unaligned =
      eval::absoluteTrajectoryError(matches, eval::Alignment::kNone).translation.rmse;
  const double se3 = eval::absoluteTrajectoryError(matches, eval::Alignment::kSe3).translation.rmse;
  std::printf("handheld VLP-32C rig, %.1f m: ATE %.4f m unaligned, %.4f m SE(3)\n",
              result.path_length, unaligned, se3);
  EXPECT_GE(run.trajectory.size() + 3, static_cast<std::size_t>(result.scans));
  EXPECT_LT(se3, 0.05);
  EXPECT_LT(unaligned, 0.10) << "same world frame as the truth without alignment";
}

TEST(SimOutput, CaptureIsForVelodyneModelsOnly) {
  BuildingSpec spec = loadBuildingSpec("tiny");
  spec.sensors.lidar.model = LidarModel::kOs1_64;
  SimulationOptions options;
  options.max_duration = 0.5;
  options.formats.pcap = true;
  const test::TempDir dir;
  const fs::path out = dir.path() / "pcap_os1";
  try {
    simulate(spec, options, out.string());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("OS1-64"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace storey::sim
