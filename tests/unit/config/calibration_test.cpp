#include "config/config.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/error.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

// The example of DESIGN.md, verbatim.
const char* kDesignExample = R"(# Storey sensor calibration, format version 1
T_imu_lidar:                  # pose of the LiDAR frame in the IMU frame
  translation: [0.25, 0.0, 0.12]            # metres
  rotation_xyzw: [0.0, 0.0, 0.0, 1.0]       # unit quaternion, Hamilton, x y z w
time_offset_lidar_to_imu: 0.0 # seconds; t_imu = t_lidar + offset
imu:
  rate_hz: 400
  gyro_noise_density: 1.75e-4     # rad/s/sqrt(Hz)
  accel_noise_density: 5.9e-4     # m/s^2/sqrt(Hz)
  gyro_random_walk: 1.0e-5        # rad/s^2/sqrt(Hz)
  accel_random_walk: 1.0e-4       # m/s^3/sqrt(Hz)
  gravity: 9.81                   # m/s^2
lidar:
  model: VLP-16                   # VLP-16 | HDL-32E | OS1-64 | generic
topics:                           # optional; auto-detected when absent
  points: /velodyne_points
  imu: /imu/data
)";

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Calibration, ReadsTheDesignExample) {
  test::TempDir dir;
  Config config;
  applyCalibrationFile(config, dir.write("calibration.yaml", kDesignExample));
  EXPECT_TRUE(config.sensor.T_imu_lidar.translation().isApprox(Eigen::Vector3d(0.25, 0.0, 0.12)));
  EXPECT_NEAR(config.sensor.T_imu_lidar.angle(), 0.0, 1e-12);
  EXPECT_EQ(config.input.points_topic, "/velodyne_points");
  EXPECT_EQ(config.input.imu_topic, "/imu/data");
  EXPECT_EQ(config.sensor.lidar_model, LidarModel::kVlp16);
  EXPECT_EQ(config.sensor.imu.rate_hz, 400.0);
}

TEST(Calibration, OptionalKeysKeepConfigValues) {
  test::TempDir dir;
  Config config;
  config.sensor.imu.rate_hz = 200.0;
  config.input.imu_topic = "/my_imu";
  config.input.velodyne_cut_angle_deg = 90.0;
  applyCalibrationFile(config, dir.write("c.yaml",
                                         "T_imu_lidar:\n  translation: [1, 2, 3]\n"
                                         "  rotation_xyzw: [0, 0, 1, 0]\n"));
  EXPECT_EQ(config.sensor.imu.rate_hz, 200.0);
  EXPECT_EQ(config.input.imu_topic, "/my_imu");
  EXPECT_EQ(config.input.velodyne_cut_angle_deg, 90.0);
  EXPECT_NEAR(config.sensor.T_imu_lidar.angle(), M_PI, 1e-12);
}

TEST(Calibration, WriteReadRoundTrip) {
  test::TempDir dir;
  Config written;
  written.sensor.T_imu_lidar =
      Pose(Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -2, 0.5).normalized())),
           Eigen::Vector3d(0.3, -0.1, 0.2));
  written.sensor.time_offset_lidar_to_imu = -0.0125;
  written.sensor.imu.rate_hz = 200.0;
  written.sensor.imu.gyro_noise_density = 3e-3;
  written.sensor.lidar_model = LidarModel::kHdl32e;
  written.input.points_topic = "/points";
  written.input.velodyne_cut_angle_deg = 180.0;
  const std::string path = dir.file("calibration.yaml");
  writeCalibrationFile(calibrationOf(written), path);
  Config read;
  applyCalibrationFile(read, path);
  EXPECT_TRUE(read.sensor.T_imu_lidar.isApprox(written.sensor.T_imu_lidar, 1e-12, 1e-12));
  EXPECT_EQ(read.sensor.time_offset_lidar_to_imu, -0.0125);
  EXPECT_EQ(read.sensor.imu.rate_hz, 200.0);
  EXPECT_EQ(read.sensor.imu.gyro_noise_density, 3e-3);
  EXPECT_EQ(read.sensor.lidar_model, LidarModel::kHdl32e);
  EXPECT_EQ(read.input.points_topic, "/points");
  EXPECT_EQ(read.input.imu_topic, "");
  EXPECT_EQ(read.input.velodyne_cut_angle_deg, 180.0);
  // No temporary files left next to it.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);
}

struct BadCase {
  const char* name;
  const char* text;
  const char* expected_fragment;
};

TEST(Calibration, BadFilesNameTheKeyAtFault) {
  const BadCase cases[] = {
      {"missing extrinsic", "imu:\n  rate_hz: 400\n", "'T_imu_lidar'"},
      {"missing rotation", "T_imu_lidar:\n  translation: [0, 0, 0]\n", "T_imu_lidar.rotation_xyzw"},
      {"non-unit quaternion",
       "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 0, 2]\n",
       "T_imu_lidar.rotation_xyzw"},
      {"wrong length", "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 1]\n",
       "T_imu_lidar.rotation_xyzw"},
      {"unknown key",
       "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 0, 1]\ntime_ofset: 0.1\n",
       "'time_ofset'"},
      {"nested unknown key",
       "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 0, 1]\nimu:\n  rate: 100\n",
       "'imu.rate'"},
      {"wrong type",
       "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 0, 1]\nimu:\n  gravity: "
       "strong\n",
       "'imu.gravity'"},
      {"bad model",
       "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 0, 1]\nlidar:\n  model: "
       "VLP-32\n",
       "'lidar.model'"},
      {"cut angle out of range",
       "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 0, 1]\nlidar:\n  "
       "cut_angle_deg: 360\n",
       "'lidar.cut_angle_deg' (line 5)"},
      {"offset out of range",
       "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 0, "
       "1]\ntime_offset_lidar_to_imu: 5\n",
       "time_offset_lidar_to_imu"},
      {"empty", "", "empty"},
      {"not a mapping", "- 1\n- 2\n", "mapping"},
  };
  test::TempDir dir;
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = dir.write("bad.yaml", c.text);
    Config config;
    config.input.points_topic = "/unchanged";
    const std::string message = errorOf([&] { applyCalibrationFile(config, path); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(c.expected_fragment), std::string::npos) << message;
    EXPECT_EQ(config.input.points_topic, "/unchanged") << "config must be untouched on error";
  }
}

}  // namespace
}  // namespace storey
