#include "unit/io/bag_fixtures.h"

#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/String.h>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace storey::test {
namespace {

ros::Time rosTime(std::int64_t ns) {
  ros::Time t;
  t.fromNSec(static_cast<std::uint64_t>(ns));
  return t;
}

}  // namespace

struct TestBagWriter::Impl {
  rosbag::Bag bag;
};

TestBagWriter::TestBagWriter(const std::string& path, TestCompression compression,
                             std::uint32_t chunk_bytes)
    : impl_(std::make_unique<Impl>()) {
  impl_->bag.open(path, rosbag::bagmode::Write);
  impl_->bag.setChunkThreshold(chunk_bytes);
  switch (compression) {
    case TestCompression::kNone:
      impl_->bag.setCompression(rosbag::compression::Uncompressed);
      break;
    case TestCompression::kLz4:
      impl_->bag.setCompression(rosbag::compression::LZ4);
      break;
    case TestCompression::kBz2:
      impl_->bag.setCompression(rosbag::compression::BZ2);
      break;
  }
}

TestBagWriter::~TestBagWriter() {
  close();
}

void TestBagWriter::write(const std::string& topic, std::int64_t record_ns,
                          const TestCloud& cloud) {
  sensor_msgs::PointCloud2 msg;
  msg.header.stamp = rosTime(cloud.stamp_ns);
  msg.header.frame_id = cloud.frame_id;
  msg.height = cloud.height;
  msg.width = cloud.width;
  for (const auto& f : cloud.fields) {
    sensor_msgs::PointField pf;
    pf.name = f.name;
    pf.offset = f.offset;
    pf.datatype = f.datatype;
    pf.count = f.count;
    msg.fields.push_back(pf);
  }
  msg.is_bigendian = cloud.is_bigendian;
  msg.point_step = cloud.point_step;
  msg.row_step = cloud.row_step;
  msg.data = cloud.data;
  msg.is_dense = false;
  impl_->bag.write(topic, rosTime(record_ns), msg);
}

void TestBagWriter::write(const std::string& topic, std::int64_t record_ns, const TestImu& imu) {
  sensor_msgs::Imu msg;
  msg.header.stamp = rosTime(imu.stamp_ns);
  msg.header.frame_id = "imu";
  msg.orientation.w = 1.0;
  msg.orientation_covariance[0] = -1.0;
  msg.angular_velocity.x = imu.gyro.x();
  msg.angular_velocity.y = imu.gyro.y();
  msg.angular_velocity.z = imu.gyro.z();
  msg.linear_acceleration.x = imu.accel.x();
  msg.linear_acceleration.y = imu.accel.y();
  msg.linear_acceleration.z = imu.accel.z();
  if (imu.gyro_missing) msg.angular_velocity_covariance[0] = -1.0;
  impl_->bag.write(topic, rosTime(record_ns), msg);
}

void TestBagWriter::writeString(const std::string& topic, std::int64_t record_ns,
                                const std::string& text) {
  std_msgs::String msg;
  msg.data = text;
  impl_->bag.write(topic, rosTime(record_ns), msg);
}

void TestBagWriter::close() {
  if (impl_ && impl_->bag.isOpen()) impl_->bag.close();
}

VelodynePoint velodyneImuBagPoint(int s, int k, int points_per_scan) {
  const int columns = std::max(1, points_per_scan / 16);
  const int ring = k % 16;
  const int column = k / 16;
  const double azimuth = -2.0 * M_PI * column / columns;  // clockwise
  const double elevation = (-15.0 + 2.0 * ring) * M_PI / 180.0;
  const double range = 5.0 + 0.25 * s + 0.01 * ring;
  VelodynePoint p;
  p.x = static_cast<float>(range * std::cos(elevation) * std::cos(azimuth));
  p.y = static_cast<float>(range * std::cos(elevation) * std::sin(azimuth));
  p.z = static_cast<float>(range * std::sin(elevation));
  p.intensity = static_cast<float>(k % 256);
  p.ring = static_cast<std::uint16_t>(ring);
  p.time = static_cast<float>(0.1 * column / columns);
  return p;
}

TestImu velodyneImuBagImu(const VelodyneImuBag& spec, int i) {
  TestImu imu;
  imu.stamp_ns = spec.start_ns + static_cast<std::int64_t>(i) * 100'000'000 / spec.imu_per_scan;
  imu.gyro = Eigen::Vector3d(0.01 * i, -0.02, 0.5);
  imu.accel = Eigen::Vector3d(0.1, 0.0, 9.81);
  return imu;
}

void writeVelodyneImuBag(const std::string& path, const VelodyneImuBag& spec) {
  // Write in record-time order, as `rosbag record` does.
  struct Pending {
    std::int64_t record_ns;
    int scan;  ///< -1 for IMU
    int imu;
  };
  std::vector<Pending> pending;
  for (int s = 0; s < spec.scans; ++s) {
    pending.push_back({spec.start_ns + s * 100'000'000LL + 100'000'000LL, s, -1});
  }
  for (int i = 0; i < spec.scans * spec.imu_per_scan; ++i) {
    pending.push_back({velodyneImuBagImu(spec, i).stamp_ns + 1'000'000, -1, i});
  }
  std::stable_sort(pending.begin(), pending.end(),
                   [](const Pending& a, const Pending& b) { return a.record_ns < b.record_ns; });
  TestBagWriter bag(path, spec.compression, spec.chunk_bytes);
  for (const Pending& p : pending) {
    if (p.scan >= 0) {
      std::vector<VelodynePoint> points;
      for (int k = 0; k < spec.points_per_scan; ++k) {
        points.push_back(velodyneImuBagPoint(p.scan, k, spec.points_per_scan));
      }
      bag.write(spec.points_topic, p.record_ns,
                velodyneCloud(spec.start_ns + p.scan * 100'000'000LL, points));
    } else {
      bag.write(spec.imu_topic, p.record_ns, velodyneImuBagImu(spec, p.imu));
    }
  }
  bag.close();
}

std::string makeTempDir(const std::string& name) {
  static std::atomic<int> counter{0};
  const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
  std::ostringstream dir_name;
  dir_name << "storey_" << name << "_" << ::getpid() << "_" << now << "_" << counter++;
  const auto dir = std::filesystem::temp_directory_path() / dir_name.str();
  std::filesystem::create_directories(dir);
  return dir.string();
}

void writeFileBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::string readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void truncatedCopy(const std::string& from, const std::string& to, std::uint64_t size) {
  const std::string bytes = readFileBytes(from);
  if (size > bytes.size()) throw std::logic_error("truncatedCopy: size beyond the file");
  writeFileBytes(to, bytes.substr(0, size));
}

}  // namespace storey::test
