// CDR (XCDR1, both byte orders, alignment) and ROS 1 serialization of
// PointCloud2, Imu and VelodyneScan: hand-built bytes from the OMG CDR rules,
// round trips, and damaged messages.
#include <gtest/gtest.h>

#include <cstring>

#include "common/error.h"
#include "io/ros_message_codec.h"
#include "io/ros_wire.h"

namespace storey {
namespace {

/// Big-endian CDR bytes built by hand: encapsulation 0x0000, aligned fields.
struct BigEndianCdr {
  std::vector<std::uint8_t> b{0x00, 0x00, 0x00, 0x00};
  void align(std::size_t n) {
    while ((b.size() - 4) % n != 0) b.push_back(0xAA);  // padding of any value
  }
  void u8(std::uint8_t v) { b.push_back(v); }
  void u32(std::uint32_t v) {
    align(4);
    for (int k = 3; k >= 0; --k) b.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void f64(double d) {
    align(8);
    std::uint64_t v;
    std::memcpy(&v, &d, 8);
    for (int k = 7; k >= 0; --k) b.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    b.insert(b.end(), s.begin(), s.end());
    b.push_back(0);
  }
};

TEST(RosCodec, BigEndianCdrImuWithAlignmentPadding) {
  BigEndianCdr m;
  m.u32(1700000000);  // stamp.sec
  m.u32(250);         // stamp.nanosec
  m.str("imu_link");  // 4 + 9 bytes: the orientation then needs 3 padding bytes to align to 8
  for (double v : {0.0, 0.0, 0.0, 1.0}) m.f64(v);
  for (int i = 0; i < 9; ++i) m.f64(0.0);
  for (double v : {0.1, -0.2, 0.3}) m.f64(v);
  for (int i = 0; i < 9; ++i) m.f64(i == 0 ? -1.0 : 0.0);  // no gyro data
  for (double v : {0.5, 0.25, 9.81}) m.f64(v);
  for (int i = 0; i < 9; ++i) m.f64(0.01);
  // 4 encapsulation + 8 stamp + 4 + 9 frame_id + 3 padding + 37 doubles.
  ASSERT_EQ(m.b.size(), 4u + 8u + 13u + 3u + 37u * 8u) << "fixture layout";
  const ImuMessage imu = decodeImu(m.b.data(), m.b.size(), WireFormat::kCdr);
  EXPECT_EQ(imu.sample.stamp_ns, 1700000000LL * 1000000000LL + 250);
  EXPECT_DOUBLE_EQ(imu.sample.gyro.y(), -0.2);
  EXPECT_DOUBLE_EQ(imu.sample.accel.z(), 9.81);
  EXPECT_FALSE(imu.has_gyro);
  EXPECT_TRUE(imu.has_accel);
}

TEST(RosCodec, BigEndianCdrPointCloudFields) {
  BigEndianCdr m;
  m.u32(5);
  m.u32(6);
  m.str("lidar");
  m.u32(1);  // height
  m.u32(2);  // width
  m.u32(1);  // one field
  m.str("x");
  m.u32(0);
  m.u8(7);
  m.u32(1);  // count, aligned after the uint8
  m.u8(1);   // is_bigendian
  m.u32(4);
  m.u32(8);
  m.u32(8);
  for (int i = 0; i < 8; ++i) m.u8(static_cast<std::uint8_t>(i));
  m.u8(1);
  PointCloudMessage cloud;
  decodePointCloud2(m.b.data(), m.b.size(), WireFormat::kCdr, cloud);
  EXPECT_EQ(cloud.stamp_ns, 5LL * 1000000000LL + 6);
  EXPECT_EQ(cloud.frame_id, "lidar");
  ASSERT_EQ(cloud.fields.size(), 1u);
  EXPECT_EQ(cloud.fields[0].name, "x");
  EXPECT_EQ(cloud.fields[0].datatype, 7);
  EXPECT_EQ(cloud.fields[0].count, 1u);
  EXPECT_TRUE(cloud.is_bigendian);
  EXPECT_EQ(cloud.width, 2u);
  EXPECT_EQ(cloud.data.size(), 8u);
  EXPECT_EQ(cloud.data[7], 7);
}

PointCloudMessage sampleCloud() {
  PointCloudMessage c;
  c.stamp_ns = 1'700'000'123'456'789LL;
  c.frame_id = "velodyne";
  c.height = 1;
  c.width = 3;
  c.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"ring", 12, 4, 1}};
  c.point_step = 16;
  c.row_step = 48;
  c.data.resize(48);
  for (std::size_t i = 0; i < c.data.size(); ++i) c.data[i] = static_cast<std::uint8_t>(i * 7);
  return c;
}

TEST(RosCodec, RoundTripsInBothEncodings) {
  for (WireFormat format : {WireFormat::kCdr, WireFormat::kRos1}) {
    const PointCloudMessage c = sampleCloud();
    const auto bytes = encodePointCloud2(c, format);
    PointCloudMessage back;
    decodePointCloud2(bytes.data(), bytes.size(), format, back);
    EXPECT_EQ(back.stamp_ns, c.stamp_ns);
    EXPECT_EQ(back.frame_id, c.frame_id);
    EXPECT_EQ(back.fields, c.fields);
    EXPECT_EQ(back.data, c.data);
    EXPECT_EQ(back.row_step, c.row_step);

    ImuSample s;
    s.stamp_ns = 42;
    s.gyro = {1, 2, 3};
    s.accel = {4, 5, 6};
    const auto imu_bytes = encodeImu(s, "imu", 0.1, 0.2, nullptr, nullptr, format);
    const ImuMessage imu = decodeImu(imu_bytes.data(), imu_bytes.size(), format);
    EXPECT_EQ(imu.sample.stamp_ns, 42);
    EXPECT_EQ(imu.sample.gyro, s.gyro);
    EXPECT_EQ(imu.sample.accel, s.accel);

    VelodyneScanMessage scan;
    scan.stamp_ns = 99'000'000'007LL;
    scan.frame_id = "velodyne";
    scan.packets.resize(2);
    scan.packets[1].stamp_ns = 98'000'000'001LL;
    scan.packets[1].data[1205] = 0x22;
    const auto scan_bytes = encodeVelodyneScan(scan, format);
    VelodyneScanMessage scan_back;
    decodeVelodyneScan(scan_bytes.data(), scan_bytes.size(), format, scan_back);
    ASSERT_EQ(scan_back.packets.size(), 2u);
    EXPECT_EQ(scan_back.packets[1].stamp_ns, scan.packets[1].stamp_ns);
    EXPECT_EQ(scan_back.packets[1].data, scan.packets[1].data);
  }
}

TEST(RosCodec, CdrLayoutFollowsTheAlignmentRules) {
  // Header: 4 (encapsulation) + 8 (stamp) + 4 + 9 ("velodyne\0"), then height
  // aligned to 4: starts at offset 28 of the message (24 after the header).
  const auto bytes = encodePointCloud2(sampleCloud(), WireFormat::kCdr);
  EXPECT_EQ(bytes[0], 0x00);
  EXPECT_EQ(bytes[1], 0x01);
  EXPECT_EQ(bytes[28], 1);  // height, little-endian
  EXPECT_EQ(bytes[32], 3);  // width
}

TEST(RosCodec, DamagedMessagesAreErrorsNamingTheField) {
  auto bytes = encodePointCloud2(sampleCloud(), WireFormat::kCdr);
  PointCloudMessage out;
  for (std::size_t cut : {std::size_t{0}, std::size_t{3}, std::size_t{30}, bytes.size() - 10}) {
    try {
      decodePointCloud2(bytes.data(), cut, WireFormat::kCdr, out);
      ADD_FAILURE() << "no error at " << cut;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("byte"), std::string::npos) << e.what();
    }
  }
  // A sequence length larger than the message: an error, not an allocation.
  auto huge = bytes;
  huge[36] = huge[37] = huge[38] = 0xFF;  // fields count
  EXPECT_THROW(decodePointCloud2(huge.data(), huge.size(), WireFormat::kCdr, out), Error);
  // XCDR2 and parameter lists are refused by name.
  bytes[1] = 0x07;
  try {
    decodePointCloud2(bytes.data(), bytes.size(), WireFormat::kCdr, out);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("XCDR2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace storey
