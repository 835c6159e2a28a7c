#include "sim/bag_writer.h"

#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/PointField.h>

#include <cstring>
#include <vector>

#include "common/error.h"
#include "io/ros_message_codec.h"

namespace storey::sim {

struct BagWriter::Impl {
  rosbag::Bag bag;
  std::uint32_t scan_seq = 0;
  std::uint32_t imu_seq = 0;
  std::uint32_t packet_seq = 0;
};

namespace {

/// A velodyne_msgs/VelodyneScan already serialized (io/ros_message_codec.h):
/// librosbag writes its bytes as they are, under the type's name, MD5 and definition.
struct RawVelodyneScan {
  std::vector<std::uint8_t> bytes;
};

}  // namespace
}  // namespace storey::sim

namespace ros {
namespace message_traits {
template <>
struct MD5Sum<storey::sim::RawVelodyneScan> {
  // md5 of the type's text with nested types replaced by their MD5s (ROS 1's rule).
  static const char* value() { return "50804fc9533a0e579e6322c04ae70566"; }
  static const char* value(const storey::sim::RawVelodyneScan&) { return value(); }
};
template <>
struct DataType<storey::sim::RawVelodyneScan> {
  static const char* value() { return "velodyne_msgs/VelodyneScan"; }
  static const char* value(const storey::sim::RawVelodyneScan&) { return value(); }
};
template <>
struct Definition<storey::sim::RawVelodyneScan> {
  static const char* value() {
    return storey::rosMessageDefinition(storey::kVelodyneScanType, storey::WireFormat::kRos1);
  }
  static const char* value(const storey::sim::RawVelodyneScan&) { return value(); }
};
}  // namespace message_traits
namespace serialization {
template <>
struct Serializer<storey::sim::RawVelodyneScan> {
  template <typename Stream>
  static void write(Stream& stream, const storey::sim::RawVelodyneScan& m) {
    std::memcpy(stream.advance(static_cast<std::uint32_t>(m.bytes.size())), m.bytes.data(),
                m.bytes.size());
  }
  static std::uint32_t serializedLength(const storey::sim::RawVelodyneScan& m) {
    return static_cast<std::uint32_t>(m.bytes.size());
  }
};
}  // namespace serialization
}  // namespace ros

namespace storey::sim {
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
    throw Error(path + ": cannot write " + what + ": " + e.what() + " (disk full?)");
  }
}

}  // namespace

void BagWriter::abandon(std::unique_ptr<Impl> impl) {
  // rosbag::Bag closes again in its own destructor and throws out of it when
  // that fails too (std::terminate): a bag that could not be written (a full
  // disk) is never destroyed, only kept reachable until the process ends,
  // which releases its file.
  static auto* const unfinished = new std::vector<Impl*>();
  unfinished->push_back(impl.release());
}

BagWriter::BagWriter(const std::string& path, BagCompression compression)
    : impl_(std::make_unique<Impl>()), path_(path) {
  try {
    impl_->bag.open(path, rosbag::bagmode::Write);
    impl_->bag.setCompression(compression == BagCompression::kLz4
                                  ? rosbag::compression::LZ4
                                  : rosbag::compression::Uncompressed);
  } catch (const std::exception& e) {
    abandon(std::move(impl_));
    throw Error(path + ": cannot open the bag for writing: " + e.what() + " (disk full?)");
  }
}

BagWriter::~BagWriter() {
  try {
    close();
  } catch (...) {
    abandon(std::move(impl_));
  }
}

void BagWriter::writeCloud(const std::string& topic, const PointCloudMessage& cloud,
                           std::int64_t receipt_ns) {
  sensor_msgs::PointCloud2 msg;
  msg.header.seq = impl_->scan_seq++;
  msg.header.stamp = rosTime(cloud.stamp_ns);
  msg.header.frame_id = cloud.frame_id;
  msg.height = cloud.height;
  msg.width = cloud.width;
  for (const auto& f : cloud.fields) msg.fields.push_back(field(f.name, f.offset, f.datatype));
  msg.is_bigendian = cloud.is_bigendian;
  msg.point_step = cloud.point_step;
  msg.row_step = cloud.row_step;
  msg.is_dense = cloud.is_dense;
  msg.data = cloud.data;
  writeMessage(impl_->bag, path_, topic, receipt_ns, msg, "a point cloud");
}

void BagWriter::writeScan(const std::string& topic, const Scan& scan, std::int64_t receipt_ns) {
  writeCloud(topic, velodyneLayoutCloud(scan), receipt_ns);
}

void BagWriter::writeOrganisedScan(const std::string& topic, const std::string& frame_id,
                                   const OrganisedScan& scan, std::int64_t stamp_ns,
                                   std::int64_t receipt_ns) {
  writeCloud(topic, ousterLayoutCloud(scan, frame_id, stamp_ns), receipt_ns);
}

void BagWriter::writeVelodyneScan(const std::string& topic, const VelodyneScanMessage& scan,
                                  std::int64_t receipt_ns) {
  const RawVelodyneScan raw{encodeVelodyneScan(scan, WireFormat::kRos1, impl_->packet_seq++)};
  writeMessage(impl_->bag, path_, topic, receipt_ns, raw, "a VelodyneScan");
}

void BagWriter::writeImu(const std::string& topic, const std::string& frame_id,
                         const ImuSample& sample, std::int64_t record_ns, double gyro_variance,
                         double accel_variance, const ImuOrientation* orientation) {
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
  writeMessage(impl_->bag, path_, topic, record_ns, msg, "an IMU message");
}

void BagWriter::close() {
  if (!impl_->bag.isOpen()) return;
  try {
    impl_->bag.close();
  } catch (const std::exception& e) {
    throw Error(path_ + ": cannot finish the bag: " + e.what() + " (disk full?)");
  }
}

}  // namespace storey::sim
