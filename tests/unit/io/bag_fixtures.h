#pragma once
/// Writing test bags with the raw librosbag API (rosbag::Bag::write of
/// sensor_msgs messages, explicit stamps), behind a header without ROS types,
/// and a few file helpers for damaged-input tests.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>

#include "unit/io/cloud_fixtures.h"

namespace storey::test {

struct TestImu {
  std::int64_t stamp_ns = 0;
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();       ///< [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d(0, 0, 9.81);  ///< [m/s^2]
  bool gyro_missing = false;  ///< angular_velocity_covariance[0] = -1 ("no data")
};

enum class TestCompression { kNone, kLz4, kBz2 };

class TestBagWriter {
 public:
  /// Opens `path` for writing; chunks are closed once they hold `chunk_bytes`.
  explicit TestBagWriter(const std::string& path,
                         TestCompression compression = TestCompression::kNone,
                         std::uint32_t chunk_bytes = 768 * 1024);
  ~TestBagWriter();
  /// Writes a sensor_msgs/PointCloud2 with record time `record_ns`.
  void write(const std::string& topic, std::int64_t record_ns, const TestCloud& cloud);
  /// Writes a sensor_msgs/Imu with record time `record_ns`.
  void write(const std::string& topic, std::int64_t record_ns, const TestImu& imu);
  /// Writes a std_msgs/String (a type without header) with record time `record_ns`.
  void writeString(const std::string& topic, std::int64_t record_ns, const std::string& text);
  /// Writes the index and closes the file.
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A small VLP-16-like log: scans at 10 Hz in the Velodyne driver layout on
/// /velodyne_points, IMU at 200 Hz on /imu/data. Scans are recorded 100 ms
/// after their stamp (end of sweep), IMU samples 1 ms after theirs.
struct VelodyneImuBag {
  std::int64_t start_ns = 1'700'000'000'000'000'000;  ///< stamp of the first scan
  int scans = 10;
  int points_per_scan = 64;  ///< 16 rings x 4 columns
  int imu_per_scan = 20;
  std::string points_topic = "/velodyne_points";
  std::string imu_topic = "/imu/data";
  TestCompression compression = TestCompression::kNone;
  std::uint32_t chunk_bytes = 768 * 1024;
};
/// Point `k` of scan `s` (the values written, for exact comparisons).
VelodynePoint velodyneImuBagPoint(int s, int k, int points_per_scan);
/// IMU sample `i` (stamp start_ns + i * 5 ms).
TestImu velodyneImuBagImu(const VelodyneImuBag& spec, int i);
void writeVelodyneImuBag(const std::string& path, const VelodyneImuBag& spec);

/// A fresh, empty directory under the system's temporary directory.
std::string makeTempDir(const std::string& name);
void writeFileBytes(const std::string& path, const std::string& bytes);
std::string readFileBytes(const std::string& path);
/// Copies the first `size` bytes of `from` to `to`.
void truncatedCopy(const std::string& from, const std::string& to, std::uint64_t size);

}  // namespace storey::test
