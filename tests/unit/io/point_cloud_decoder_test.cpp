// Decoding of PointCloud2 bytes by field descriptors: driver layouts byte for
// byte, every datatype, byte order, organised clouds, dropped points, errors.
#include "io/point_cloud_decoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "common/error.h"
#include "unit/io/cloud_fixtures.h"

namespace storey {
namespace {

using test::CloudBuilder;
using test::TestCloud;

constexpr std::int64_t kStamp = 1'700'000'000'500'000'000;  // 1700000000.5 s
const PointFilter kNoFilter{0.0, 1e12};

DecodedCloud decode(const TestCloud& cloud, const PointFilter& filter = kNoFilter) {
  const PointCloudView view = cloud.view();
  return decodePointCloud(view, resolveCloudLayout(view.fields, view.point_step), cloud.stamp_ns,
                          filter);
}

PointFieldDesc field(const char* name, std::uint32_t offset, PointFieldType type) {
  return PointFieldDesc{name, offset, static_cast<std::uint8_t>(type), 1};
}

TEST(PointCloudDecoder, VelodyneLayoutByteForByte) {
  const TestCloud cloud = test::velodyneCloud(
      kStamp,
      {{1.5f, -2.25f, 0.125f, 37.0f, 3, -0.0625f}, {-4.0f, 8.5f, -1.75f, 255.0f, 15, 0.09375f}});
  // The fixture itself: the driver's layout, padding included.
  ASSERT_EQ(cloud.point_step, 32u);
  ASSERT_EQ(cloud.data.size(), 64u);
  EXPECT_EQ(cloud.data[12], 0xEE);  // padding after z
  EXPECT_EQ(cloud.data[22], 0xEE);  // padding after ring
  EXPECT_EQ(cloud.data[28], 0xEE);  // trailing padding
  std::uint16_t ring_raw;
  std::memcpy(&ring_raw, cloud.data.data() + 32 + 20, 2);
  EXPECT_EQ(ring_raw, 15);

  const DecodedCloud out = decode(cloud);
  ASSERT_EQ(out.points.size(), 2u);
  const ScanPoint& a = out.points[0];
  EXPECT_EQ(a.p.x(), 1.5f);
  EXPECT_EQ(a.p.y(), -2.25f);
  EXPECT_EQ(a.p.z(), 0.125f);
  EXPECT_EQ(a.intensity, 37.0f);
  EXPECT_EQ(a.ring, 3);
  EXPECT_EQ(a.time, -0.0625f);
  const ScanPoint& b = out.points[1];
  EXPECT_EQ(b.p.x(), -4.0f);
  EXPECT_EQ(b.p.y(), 8.5f);
  EXPECT_EQ(b.p.z(), -1.75f);
  EXPECT_EQ(b.intensity, 255.0f);
  EXPECT_EQ(b.ring, 15);
  EXPECT_EQ(b.time, 0.09375f);
}

TEST(PointCloudDecoder, FieldOrderIsIrrelevant) {
  // Same quantities, fields listed in another order at other offsets.
  CloudBuilder builder(
      {field("time", 0, PointFieldType::kFloat64), field("ring", 8, PointFieldType::kUint8),
       field("z", 9, PointFieldType::kFloat32), field("intensity", 13, PointFieldType::kUint8),
       field("y", 14, PointFieldType::kFloat32), field("x", 18, PointFieldType::kFloat32)},
      22, 1);
  builder.set(0, "x", 2.0)
      .set(0, "y", 3.0)
      .set(0, "z", 4.0)
      .set(0, "intensity", 200)
      .set(0, "ring", 9)
      .set(0, "time", 0.05);
  const DecodedCloud out = decode(builder.build(kStamp));
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_EQ(out.points[0].p, Eigen::Vector3f(2.0f, 3.0f, 4.0f));
  EXPECT_EQ(out.points[0].intensity, 200.0f);
  EXPECT_EQ(out.points[0].ring, 9);
  EXPECT_EQ(out.points[0].time, 0.05f);
}

TEST(PointCloudDecoder, AllEightDatatypes) {
  struct Case {
    PointFieldType type;
    double value;
  };
  const Case cases[] = {{PointFieldType::kInt8, -7},        {PointFieldType::kUint8, 250},
                        {PointFieldType::kInt16, -30000},   {PointFieldType::kUint16, 60000},
                        {PointFieldType::kInt32, -2000000}, {PointFieldType::kUint32, 4000000000.0},
                        {PointFieldType::kFloat32, 0.75},   {PointFieldType::kFloat64, -123.25}};
  for (const bool big_endian : {false, true}) {
    for (const Case& c : cases) {
      SCOPED_TRACE(pointFieldTypeName(static_cast<std::uint8_t>(c.type)) +
                   (big_endian ? " big-endian" : " little-endian"));
      CloudBuilder builder({field("x", 0, c.type), field("y", 8, c.type), field("z", 16, c.type),
                            field("intensity", 24, c.type)},
                           32, 1, 1, big_endian);
      builder.set(0, "x", c.value).set(0, "y", 1).set(0, "z", 2).set(0, "intensity", c.value);
      const DecodedCloud out = decode(builder.build(kStamp));
      ASSERT_EQ(out.points.size(), 1u);
      EXPECT_EQ(out.points[0].p.x(), static_cast<float>(c.value));
      EXPECT_EQ(out.points[0].p.y(), 1.0f);
      EXPECT_EQ(out.points[0].p.z(), 2.0f);
      EXPECT_EQ(out.points[0].intensity, static_cast<float>(c.value));
    }
  }
}

TEST(PointCloudDecoder, BigEndianBytesWrittenByHand) {
  TestCloud cloud;
  cloud.stamp_ns = kStamp;
  cloud.fields = {field("x", 0, PointFieldType::kFloat32), field("y", 4, PointFieldType::kFloat32),
                  field("z", 8, PointFieldType::kFloat32),
                  field("ring", 12, PointFieldType::kUint16)};
  cloud.point_step = 14;
  cloud.width = 1;
  cloud.row_step = 14;
  cloud.is_bigendian = true;
  // 1.0f = 3F800000, 2.0f = 40000000, -0.5f = BF000000, ring 258 = 0102.
  cloud.data = {0x3F, 0x80, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00, 0xBF, 0x00, 0x00, 0x00, 0x01, 0x02};
  const DecodedCloud out = decode(cloud);
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_EQ(out.points[0].p, Eigen::Vector3f(1.0f, 2.0f, -0.5f));
  EXPECT_EQ(out.points[0].ring, 258);
}

TEST(PointCloudDecoder, OusterTimeIsNanosecondsRelative) {
  for (const auto layout : {test::OusterLayout::kLegacyRingU8, test::OusterLayout::kRingU16,
                            test::OusterLayout::kLowDataIntensityU16}) {
    const TestCloud cloud = test::ousterCloud(
        kStamp, 2, 1, {{1, 2, 3, 40, 0, 5}, {4, 5, 6, 41, 48'828'125, 6}}, layout);
    const DecodedCloud out = decode(cloud);
    ASSERT_EQ(out.points.size(), 2u);
    EXPECT_EQ(out.points[0].time, 0.0f);
    EXPECT_EQ(out.points[1].time, static_cast<float>(48'828'125 * 1e-9));
    EXPECT_EQ(out.points[1].intensity, 41.0f);
    EXPECT_EQ(out.points[0].ring, 5);
    EXPECT_EQ(out.points[1].p, Eigen::Vector3f(4, 5, 6));
  }
}

TEST(PointCloudDecoder, HesaiAbsoluteTimestampBecomesRelative) {
  const double stamp_s = 1'700'000'000.5;
  const TestCloud cloud = test::hesaiCloud(
      kStamp, {{1, 1, 1, 10, stamp_s + 0.03125, 2}, {2, 2, 2, 11, stamp_s - 0.015625, 3}});
  const DecodedCloud out = decode(cloud);
  ASSERT_EQ(out.points.size(), 2u);
  EXPECT_EQ(out.points[0].time, 0.03125f);
  EXPECT_EQ(out.points[1].time, -0.015625f);
  EXPECT_EQ(out.points[1].ring, 3);
  EXPECT_EQ(out.points[1].intensity, 11.0f);
}

TEST(PointCloudDecoder, SmallTimestampValuesAreRelative) {
  CloudBuilder builder(
      {field("x", 0, PointFieldType::kFloat32), field("y", 4, PointFieldType::kFloat32),
       field("z", 8, PointFieldType::kFloat32), field("timestamp", 12, PointFieldType::kFloat64)},
      20, 1);
  builder.set(0, "x", 1).set(0, "y", 0).set(0, "z", 0).set(0, "timestamp", 0.0625);
  const DecodedCloud out = decode(builder.build(kStamp));
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_EQ(out.points[0].time, 0.0625f);
}

TEST(PointCloudDecoder, OrganisedCloudHonoursRowStep) {
  // 2 rows x 2 points with 8 bytes of padding at the end of each row.
  CloudBuilder builder(
      {field("x", 0, PointFieldType::kFloat32), field("y", 4, PointFieldType::kFloat32),
       field("z", 8, PointFieldType::kFloat32)},
      12, 2, 2, false, 8);
  for (std::uint32_t i = 0; i < 4; ++i) builder.set(i, "x", i + 1).set(i, "y", 0).set(i, "z", 0);
  const TestCloud cloud = builder.build(kStamp);
  ASSERT_EQ(cloud.row_step, 32u);
  const DecodedCloud out = decode(cloud);
  ASSERT_EQ(out.points.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(out.points[i].p.x(), static_cast<float>(i + 1));
}

TEST(PointCloudDecoder, DropsNonFiniteZeroAndOutOfRangePoints) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const TestCloud cloud = test::velodyneCloud(kStamp, {{nan, 1, 1, 0, 0, 0},
                                                       {1, inf, 1, 0, 0, 0},
                                                       {1, 1, 1, 0, 0, nan},
                                                       {0, 0, 0, 0, 0, 0},
                                                       {0.1f, 0, 0, 0, 0, 0},
                                                       {200, 0, 0, 0, 0, 0},
                                                       {10, 0, 0, 5, 1, 0.01f}});
  const DecodedCloud out = decode(cloud, PointFilter{0.3, 120.0});
  EXPECT_EQ(out.non_finite, 3);
  EXPECT_EQ(out.no_return, 1);
  EXPECT_EQ(out.out_of_range, 2);
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_EQ(out.points[0].p.x(), 10.0f);
  EXPECT_EQ(out.points[0].ring, 1);
}

TEST(PointCloudDecoder, IntensityFallsBackToReflectivity) {
  CloudBuilder builder(
      {field("x", 0, PointFieldType::kFloat32), field("y", 4, PointFieldType::kFloat32),
       field("z", 8, PointFieldType::kFloat32), field("reflectivity", 12, PointFieldType::kUint16)},
      14, 1);
  builder.set(0, "x", 1).set(0, "y", 0).set(0, "z", 0).set(0, "reflectivity", 77);
  const DecodedCloud out = decode(builder.build(kStamp));
  ASSERT_EQ(out.points.size(), 1u);
  EXPECT_EQ(out.points[0].intensity, 77.0f);
}

TEST(PointCloudDecoder, LayoutWithoutRingOrTime) {
  const CloudLayout layout = resolveCloudLayout(test::xyzCloud(kStamp, {{1, 2, 3}}).fields, 12);
  EXPECT_FALSE(layout.ring.present);
  EXPECT_FALSE(layout.time.present);
  EXPECT_FALSE(layout.intensity.present);
}

TEST(PointCloudDecoder, MissingAxisIsAnErrorNamingIt) {
  const std::vector<PointFieldDesc> fields = {field("x", 0, PointFieldType::kFloat32),
                                              field("y", 4, PointFieldType::kFloat32),
                                              field("intensity", 8, PointFieldType::kFloat32)};
  try {
    resolveCloudLayout(fields, 12);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no 'z' field"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("x, y, intensity"), std::string::npos) << e.what();
  }
}

TEST(PointCloudDecoder, MalformedLayoutsAreErrors) {
  // A field past the end of the point.
  EXPECT_THROW(resolveCloudLayout({field("x", 0, PointFieldType::kFloat32),
                                   field("y", 4, PointFieldType::kFloat32),
                                   field("z", 10, PointFieldType::kFloat32)},
                                  12),
               Error);
  // An invalid datatype.
  EXPECT_THROW(
      resolveCloudLayout({field("x", 0, PointFieldType::kFloat32),
                          field("y", 4, PointFieldType::kFloat32), PointFieldDesc{"z", 8, 9, 1}},
                         12),
      Error);
  // Fewer bytes than width x point_step.
  TestCloud cloud = test::xyzCloud(kStamp, {{1, 2, 3}, {4, 5, 6}});
  cloud.data.resize(20);
  EXPECT_THROW(decode(cloud), Error);
  // row_step shorter than a row.
  TestCloud organised = test::xyzCloud(kStamp, {{1, 2, 3}, {4, 5, 6}});
  organised.width = 1;
  organised.height = 2;
  organised.row_step = 8;
  EXPECT_THROW(decode(organised), Error);
}

TEST(PointCloudDecoder, EmptyCloudDecodesToNoPoints) {
  const TestCloud cloud = test::velodyneCloud(kStamp, {});
  EXPECT_TRUE(decode(cloud).points.empty());
}

TEST(PointCloudDecoder, FieldTypeNames) {
  EXPECT_EQ(pointFieldTypeName(7), "float32");
  EXPECT_EQ(pointFieldTypeName(2), "uint8");
  EXPECT_EQ(pointFieldTypeName(0), "invalid(0)");
  EXPECT_EQ(pointFieldTypeSize(8), 8u);
  EXPECT_EQ(pointFieldTypeSize(9), 0u);
}

}  // namespace
}  // namespace storey
