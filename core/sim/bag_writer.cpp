#include "sim/bag_writer.h"

#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/PointField.h>

#include <cstring>

#include "common/error.h"

namespace storey::sim {

struct BagWriter::Impl {
  rosbag::Bag bag;
  std::uint32_t scan_seq = 0;
  std::uint32_t imu_seq = 0;
};

namespace {

ros::Time rosTime(std::int64_t ns) {
  ros::Time t;
  t.fromNSec(static_cast<std::uint64_t>(ns));
  return t;
}

sensor_msgs::PointField field(const std::string& name, std::uint32_t offset, std::uint8_t type) {
  sensor_msgs::PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = type;
  f.count = 1;
  return f;
}

/// Writes one message; a failure is a storey::Error naming the bag and what.
template <typename Message>
void writeMessage(rosbag::Bag& bag, const std::string& path, const std::string& topic,
                  std::int64_t record_ns, const Message& msg, const char* what) {
  try {
    bag.write(topic, rosTime(record_ns), msg);
  } catch (const std::exception& e) {
    throw Error(path + ": cannot write " + what + ": " + e.what());
  }
}

}  // namespace

BagWriter::BagWriter(const std::string& path, BagCompression compression)
    : impl_(std::make_unique<Impl>()), path_(path) {
  try {
    impl_->bag.open(path, rosbag::bagmode::Write);
    impl_->bag.setCompression(compression == BagCompression::kLz4
                                  ? rosbag::compression::LZ4
                                  : rosbag::compression::Uncompressed);
  } catch (const std::exception& e) {
    throw Error(path + ": cannot open the bag for writing: " + e.what());
  }
}

BagWriter::~BagWriter() {
  try {
    close();
  } catch (...) {
  }
}

void BagWriter::writeScan(const std::string& topic, const Scan& scan, std::int64_t receipt_ns) {
  constexpr std::uint32_t kStep = 32;
  sensor_msgs::PointCloud2 msg;
  msg.header.seq = impl_->scan_seq++;
  msg.header.stamp = rosTime(scan.stamp_ns);
  msg.header.frame_id = scan.frame_id;
  msg.height = 1;
  msg.width = static_cast<std::uint32_t>(scan.points.size());
  msg.fields = {field("x", 0, sensor_msgs::PointField::FLOAT32),
                field("y", 4, sensor_msgs::PointField::FLOAT32),
                field("z", 8, sensor_msgs::PointField::FLOAT32),
                field("intensity", 16, sensor_msgs::PointField::FLOAT32),
                field("ring", 20, sensor_msgs::PointField::UINT16),
                field("time", 24, sensor_msgs::PointField::FLOAT32)};
  msg.is_bigendian = false;
  msg.point_step = kStep;
  msg.row_step = kStep * msg.width;
  msg.is_dense = true;
  msg.data.assign(static_cast<std::size_t>(msg.row_step), 0);  // padding bytes are zero
  std::uint8_t* out = msg.data.data();
  for (const ScanPoint& p : scan.points) {
    std::memcpy(out + 0, &p.p.x(), 4);
    std::memcpy(out + 4, &p.p.y(), 4);
    std::memcpy(out + 8, &p.p.z(), 4);
    std::memcpy(out + 16, &p.intensity, 4);
    std::memcpy(out + 20, &p.ring, 2);
    std::memcpy(out + 24, &p.time, 4);
    out += kStep;
  }
  writeMessage(impl_->bag, path_, topic, receipt_ns, msg, "a point cloud");
}

void BagWriter::writeOrganisedScan(const std::string& topic, const std::string& frame_id,
                                   const OrganisedScan& scan, std::int64_t stamp_ns,
                                   std::int64_t receipt_ns) {
  sensor_msgs::PointCloud2 msg;
  msg.header.seq = impl_->scan_seq++;
  msg.header.stamp = rosTime(stamp_ns);
  msg.header.frame_id = frame_id;
  msg.height = static_cast<std::uint32_t>(scan.rows);
  msg.width = static_cast<std::uint32_t>(scan.columns);
  for (const CloudField& f : kOusterFields)
    msg.fields.push_back(field(f.name, f.offset, f.datatype));
  msg.is_bigendian = false;
  msg.point_step = kOusterPointStep;
  msg.row_step = kOusterPointStep * msg.width;
  msg.is_dense = true;
  msg.data.assign(static_cast<std::size_t>(msg.row_step) * msg.height, 0);
  std::uint8_t* out = msg.data.data();
  for (int row = 0; row < scan.rows; ++row) {
    const std::uint16_t ring = static_cast<std::uint16_t>(row);
    for (int column = 0; column < scan.columns; ++column) {
      const OrganisedPoint& p = scan.at(row, column);
      std::memcpy(out + 0, &p.p.x(), 4);
      std::memcpy(out + 4, &p.p.y(), 4);
      std::memcpy(out + 8, &p.p.z(), 4);
      std::memcpy(out + 16, &p.intensity, 4);
      std::memcpy(out + 20, &p.t_ns, 4);
      std::memcpy(out + 24, &p.reflectivity, 2);
      std::memcpy(out + 26, &ring, 2);
      std::memcpy(out + 32, &p.range_mm, 4);  // ambient (28) stays 0: no sunlight indoors
      out += kOusterPointStep;
    }
  }
  writeMessage(impl_->bag, path_, topic, receipt_ns, msg, "a point cloud");
}

void BagWriter::writeImu(const std::string& topic, const std::string& frame_id,
                         const ImuSample& sample, double gyro_variance, double accel_variance,
                         const ImuOrientation* orientation) {
  sensor_msgs::Imu msg;
  msg.header.seq = impl_->imu_seq++;
  msg.header.stamp = rosTime(sample.stamp_ns);
  msg.header.frame_id = frame_id;
  if (orientation != nullptr) {
    msg.orientation.x = orientation->q_world_imu.x();
    msg.orientation.y = orientation->q_world_imu.y();
    msg.orientation.z = orientation->q_world_imu.z();
    msg.orientation.w = orientation->q_world_imu.w();
    for (int i = 0; i < 3; ++i) msg.orientation_covariance[4 * i] = orientation->variance[i];
  } else {
    msg.orientation.w = 1.0;
    msg.orientation_covariance[0] = -1.0;
  }
  msg.angular_velocity.x = sample.gyro.x();
  msg.angular_velocity.y = sample.gyro.y();
  msg.angular_velocity.z = sample.gyro.z();
  msg.linear_acceleration.x = sample.accel.x();
  msg.linear_acceleration.y = sample.accel.y();
  msg.linear_acceleration.z = sample.accel.z();
  for (int i = 0; i < 3; ++i) {
    msg.angular_velocity_covariance[4 * i] = gyro_variance;
    msg.linear_acceleration_covariance[4 * i] = accel_variance;
  }
  writeMessage(impl_->bag, path_, topic, sample.stamp_ns, msg, "an IMU message");
}

void BagWriter::close() {
  if (!impl_->bag.isOpen()) return;
  try {
    impl_->bag.close();
  } catch (const std::exception& e) {
    throw Error(path_ + ": cannot finish the bag: " + e.what());
  }
}

}  // namespace storey::sim
