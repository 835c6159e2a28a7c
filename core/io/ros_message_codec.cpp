#include "io/ros_message_codec.h"

#include <cstring>

#include "common/error.h"

namespace storey {

std::string canonicalRosType(const std::string& type) {
  const auto pos = type.find("/msg/");
  if (pos == std::string::npos) return type;
  return type.substr(0, pos) + "/" + type.substr(pos + 5);
}

PointCloudView PointCloudMessage::view() const {
  PointCloudView v;
  v.fields = fields;
  v.height = height;
  v.width = width;
  v.point_step = point_step;
  v.row_step = row_step;
  v.is_bigendian = is_bigendian;
  v.data = data.data();
  v.size = data.size();
  return v;
}

void decodePointCloud2(const std::uint8_t* data, std::size_t size, WireFormat format,
                       PointCloudMessage& out) {
  WireReader r(data, size, format);
  out.stamp_ns = r.header(out.frame_id);
  out.height = r.u32("height");
  out.width = r.u32("width");
  // A PointField needs at least a string length, offset, datatype and count.
  const std::uint32_t n = r.sequenceLength("fields", 13);
  out.fields.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    PointFieldDesc f;
    f.name = r.string("fields.name");
    f.offset = r.u32("fields.offset");
    f.datatype = r.u8("fields.datatype");
    f.count = r.u32("fields.count");
    out.fields.push_back(std::move(f));
  }
  out.is_bigendian = r.boolean("is_bigendian");
  out.point_step = r.u32("point_step");
  out.row_step = r.u32("row_step");
  const std::uint32_t bytes = r.sequenceLength("data", 1);
  const std::uint8_t* p = r.bytes(bytes, "data");
  out.data.assign(p, p + bytes);
  out.is_dense = r.boolean("is_dense");
}

ImuMessage decodeImu(const std::uint8_t* data, std::size_t size, WireFormat format) {
  WireReader r(data, size, format);
  ImuMessage out;
  std::string frame_id;
  out.sample.stamp_ns = r.header(frame_id);
  for (int i = 0; i < 4; ++i) r.f64("orientation");
  for (int i = 0; i < 9; ++i) r.f64("orientation_covariance");
  for (int i = 0; i < 3; ++i) out.sample.gyro[i] = r.f64("angular_velocity");
  out.has_gyro = r.f64("angular_velocity_covariance") != -1.0;
  for (int i = 1; i < 9; ++i) r.f64("angular_velocity_covariance");
  for (int i = 0; i < 3; ++i) out.sample.accel[i] = r.f64("linear_acceleration");
  out.has_accel = r.f64("linear_acceleration_covariance") != -1.0;
  for (int i = 1; i < 9; ++i) r.f64("linear_acceleration_covariance");
  return out;
}

void decodeVelodyneScan(const std::uint8_t* data, std::size_t size, WireFormat format,
                        VelodyneScanMessage& out) {
  WireReader r(data, size, format);
  out.stamp_ns = r.header(out.frame_id);
  const std::uint32_t n = r.sequenceLength("packets", 8 + kVelodynePacketBytes);
  out.packets.resize(n);
  for (auto& packet : out.packets) {
    packet.stamp_ns = r.time("packets.stamp");
    std::memcpy(packet.data.data(), r.bytes(kVelodynePacketBytes, "packets.data"),
                kVelodynePacketBytes);
  }
}

std::int64_t decodeHeaderStamp(const std::uint8_t* data, std::size_t size, WireFormat format) {
  WireReader r(data, size, format);
  if (format == WireFormat::kRos1) r.u32("header.seq");
  return r.time("header.stamp");
}

std::vector<std::uint8_t> encodePointCloud2(const PointCloudMessage& cloud, WireFormat format,
                                            std::uint32_t seq) {
  WireWriter w(format);
  w.buffer().reserve(cloud.data.size() + 256);
  w.header(cloud.stamp_ns, cloud.frame_id, seq);
  w.u32(cloud.height);
  w.u32(cloud.width);
  w.u32(static_cast<std::uint32_t>(cloud.fields.size()));
  for (const auto& f : cloud.fields) {
    w.string(f.name);
    w.u32(f.offset);
    w.u8(f.datatype);
    w.u32(f.count);
  }
  w.boolean(cloud.is_bigendian);
  w.u32(cloud.point_step);
  w.u32(cloud.row_step);
  w.u32(static_cast<std::uint32_t>(cloud.data.size()));
  w.bytes(cloud.data.data(), cloud.data.size());
  w.boolean(cloud.is_dense);
  return w.take();
}

std::vector<std::uint8_t> encodeImu(const ImuSample& sample, const std::string& frame_id,
                                    double gyro_variance, double accel_variance,
                                    const double* orientation_xyzw,
                                    const double* orientation_variance, WireFormat format,
                                    std::uint32_t seq) {
  WireWriter w(format);
  w.header(sample.stamp_ns, frame_id, seq);
  const double identity[4] = {0, 0, 0, 1};
  for (int i = 0; i < 4; ++i) w.f64(orientation_xyzw ? orientation_xyzw[i] : identity[i]);
  for (int i = 0; i < 9; ++i) {
    double c = 0.0;
    if (!orientation_xyzw && i == 0) c = -1.0;
    if (orientation_xyzw && orientation_variance && i % 4 == 0) c = orientation_variance[i / 4];
    w.f64(c);
  }
  for (int i = 0; i < 3; ++i) w.f64(sample.gyro[i]);
  for (int i = 0; i < 9; ++i) w.f64(i % 4 == 0 ? gyro_variance : 0.0);
  for (int i = 0; i < 3; ++i) w.f64(sample.accel[i]);
  for (int i = 0; i < 9; ++i) w.f64(i % 4 == 0 ? accel_variance : 0.0);
  return w.take();
}

std::vector<std::uint8_t> encodeVelodyneScan(const VelodyneScanMessage& scan, WireFormat format,
                                             std::uint32_t seq) {
  WireWriter w(format);
  w.buffer().reserve(scan.packets.size() * (kVelodynePacketBytes + 8) + 64);
  w.header(scan.stamp_ns, scan.frame_id, seq);
  w.u32(static_cast<std::uint32_t>(scan.packets.size()));
  for (const auto& packet : scan.packets) {
    w.time(packet.stamp_ns);
    w.bytes(packet.data.data(), packet.data.size());
  }
  return w.take();
}

namespace {

constexpr const char* kHeaderRos1 =
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "uint32 seq\n"
    "time stamp\n"
    "string frame_id\n";
constexpr const char* kHeaderRos2 =
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "builtin_interfaces/Time stamp\n"
    "string frame_id\n"
    "================================================================================\n"
    "MSG: builtin_interfaces/Time\n"
    "int32 sec\n"
    "uint32 nanosec\n";

}  // namespace

const char* rosMessageDefinition(const std::string& canonical_type, WireFormat format) {
  const bool ros1 = format == WireFormat::kRos1;
  static const std::string cloud1 =
      std::string(
          "Header header\nuint32 height\nuint32 width\n"
          "PointField[] fields\nbool is_bigendian\nuint32 "
          "point_step\nuint32 row_step\nuint8[] data\nbool "
          "is_dense\n") +
      kHeaderRos1 +
      "================================================================"
      "================\nMSG: sensor_msgs/PointField\n"
      "uint8 INT8=1\nuint8 UINT8=2\nuint8 INT16=3\nuint8 UINT16=4\n"
      "uint8 INT32=5\nuint8 UINT32=6\nuint8 FLOAT32=7\nuint8 "
      "FLOAT64=8\nstring name\nuint32 offset\nuint8 datatype\n"
      "uint32 count\n";
  static const std::string cloud2 =
      std::string(
          "std_msgs/Header header\nuint32 height\nuint32 width\n"
          "sensor_msgs/PointField[] fields\nbool is_bigendian\n"
          "uint32 point_step\nuint32 row_step\nuint8[] data\nbool "
          "is_dense\n") +
      kHeaderRos2 +
      "================================================================"
      "================\nMSG: sensor_msgs/PointField\n"
      "uint8 INT8=1\nuint8 UINT8=2\nuint8 INT16=3\nuint8 UINT16=4\n"
      "uint8 INT32=5\nuint8 UINT32=6\nuint8 FLOAT32=7\nuint8 "
      "FLOAT64=8\nstring name\nuint32 offset\nuint8 datatype\n"
      "uint32 count\n";
  static const std::string imu_body =
      "geometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
      "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
      "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n";
  static const std::string imu_nested =
      "================================================================================\n"
      "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"
      "================================================================================\n"
      "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n";
  static const std::string imu1 = "Header header\n" + imu_body + kHeaderRos1 + imu_nested;
  static const std::string imu2 = "std_msgs/Header header\n" + imu_body + kHeaderRos2 + imu_nested;
  static const std::string scan1 =
      std::string("Header header\nVelodynePacket[] packets\n") + kHeaderRos1 +
      "================================================================================\n"
      "MSG: velodyne_msgs/VelodynePacket\ntime stamp\nuint8[1206] data\n";
  static const std::string scan2 =
      std::string("std_msgs/Header header\nvelodyne_msgs/VelodynePacket[] packets\n") +
      kHeaderRos2 +
      "================================================================================\n"
      "MSG: velodyne_msgs/VelodynePacket\nbuiltin_interfaces/Time stamp\nuint8[1206] data\n";
  if (canonical_type == kPointCloud2Type) return (ros1 ? cloud1 : cloud2).c_str();
  if (canonical_type == kImuType) return (ros1 ? imu1 : imu2).c_str();
  if (canonical_type == kVelodyneScanType) return (ros1 ? scan1 : scan2).c_str();
  throw Error("no message definition for " + canonical_type);
}

}  // namespace storey
