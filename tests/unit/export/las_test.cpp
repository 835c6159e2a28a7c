// LAS 1.4 written by us, read back by an independent minimal reader written
// here from the ASPRS LAS 1.4 R15 tables (not from the writer's code).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "export/point_cloud_writers.h"
#include "export_fixtures.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

struct Bytes {
  std::vector<char> data;
  template <typename T>
  T at(std::size_t offset) const {
    T v;
    EXPECT_LE(offset + sizeof(T), data.size());
    std::memcpy(&v, data.data() + offset, sizeof(T));
    return v;
  }
  std::string chars(std::size_t offset, std::size_t n) const {
    std::string s(data.data() + offset, n);
    return s.substr(0, s.find('\0'));
  }
};

Bytes readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::vector<char>(std::istreambuf_iterator<char>(in), {})};
}

TEST(Las, HeaderVlrAndRecordsRoundTrip) {
  test::TempDir dir;
  const MapCloud cloud = test::sampleCloud();
  const std::string path = dir.file("map.las");
  writeLas(path, cloud);
  const Bytes f = readAll(path);

  // Public header block (LAS 1.4 R15, table 3), by byte offset.
  ASSERT_GE(f.data.size(), 375u);
  EXPECT_EQ(f.chars(0, 4), "LASF");
  EXPECT_EQ(f.at<std::uint16_t>(6) & 0x10, 0x10);  // WKT bit, required with PDRF 6
  EXPECT_EQ(f.at<std::uint8_t>(24), 1);            // version 1.4
  EXPECT_EQ(f.at<std::uint8_t>(25), 4);
  EXPECT_EQ(f.at<std::uint16_t>(94), 375);  // header size
  const std::uint32_t point_offset = f.at<std::uint32_t>(96);
  EXPECT_EQ(f.at<std::uint32_t>(100), 1u);  // VLRs
  EXPECT_EQ(f.at<std::uint8_t>(104), 6);    // point data record format
  const std::uint16_t record_length = f.at<std::uint16_t>(105);
  EXPECT_EQ(record_length, 30 + 7);
  EXPECT_EQ(f.at<std::uint32_t>(107), 0u);  // legacy count: 0 with PDRF 6
  for (int r = 0; r < 5; ++r) EXPECT_EQ(f.at<std::uint32_t>(111 + 4 * r), 0u);
  double scale[3], offset[3];
  for (int a = 0; a < 3; ++a) {
    scale[a] = f.at<double>(131 + 8 * a);
    offset[a] = f.at<double>(155 + 8 * a);
    EXPECT_DOUBLE_EQ(scale[a], 0.001);
  }
  const double max_x = f.at<double>(179), min_x = f.at<double>(187);
  const double max_y = f.at<double>(195), min_y = f.at<double>(203);
  const double max_z = f.at<double>(211), min_z = f.at<double>(219);
  EXPECT_EQ(f.at<std::uint64_t>(247), cloud.size());  // number of point records
  EXPECT_EQ(f.at<std::uint64_t>(255), cloud.size());  // of return 1
  for (int r = 1; r < 15; ++r) EXPECT_EQ(f.at<std::uint64_t>(255 + 8 * r), 0u);
  EXPECT_EQ(f.data.size(), point_offset + cloud.size() * record_length);

  // Extra bytes VLR (record ID 4 of LASF_Spec): three 192-byte descriptors.
  const std::size_t vlr = 375;
  EXPECT_EQ(f.chars(vlr + 2, 16), "LASF_Spec");
  EXPECT_EQ(f.at<std::uint16_t>(vlr + 18), 4);
  EXPECT_EQ(f.at<std::uint16_t>(vlr + 20), 3 * 192);
  EXPECT_EQ(point_offset, vlr + 54 + 3 * 192);
  const std::size_t d = vlr + 54;
  EXPECT_EQ(f.at<std::uint8_t>(d + 2), 4);  // int16
  EXPECT_EQ(f.chars(d + 4, 32), "storey");
  EXPECT_EQ(f.at<std::uint8_t>(d + 3) & 1, 1);  // no_data valid
  EXPECT_EQ(f.at<std::int64_t>(d + 40), -1);
  EXPECT_EQ(f.at<std::uint8_t>(d + 192 + 2), 6);  // int32
  EXPECT_EQ(f.chars(d + 192 + 4, 32), "keyframe");
  EXPECT_EQ(f.at<std::uint8_t>(d + 384 + 2), 1);  // uint8
  EXPECT_EQ(f.chars(d + 384 + 4, 32), "flags");

  // Records (PDRF 6, table 14) and the extra bytes after them.
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const std::size_t r = point_offset + i * record_length;
    double xyz[3];
    for (int a = 0; a < 3; ++a) {
      xyz[a] = f.at<std::int32_t>(r + 4 * a) * scale[a] + offset[a];
      lo[a] = std::min(lo[a], xyz[a]);
      hi[a] = std::max(hi[a], xyz[a]);
      EXPECT_NEAR(xyz[a], cloud.positions[i][a], 0.0005 + 1e-4);
    }
    EXPECT_EQ(f.at<std::uint16_t>(r + 12), static_cast<std::uint16_t>(cloud.intensity[i]));
    EXPECT_EQ(f.at<std::uint8_t>(r + 14), 0x11);  // return 1 of 1
    const std::int16_t storey = cloud.storey[i];
    EXPECT_EQ(f.at<std::uint8_t>(r + 17), storey < 0 ? 255 : storey);  // user data
    EXPECT_DOUBLE_EQ(f.at<double>(r + 22), cloud.time[i]);             // GPS time
    EXPECT_EQ(f.at<std::int16_t>(r + 30), storey);
    EXPECT_EQ(f.at<std::int32_t>(r + 32), cloud.keyframe[i]);
    EXPECT_EQ(f.at<std::uint8_t>(r + 36), cloud.flags[i]);
  }
  EXPECT_NEAR(min_x, lo[0], 1e-9);
  EXPECT_NEAR(max_x, hi[0], 1e-9);
  EXPECT_NEAR(min_y, lo[1], 1e-9);
  EXPECT_NEAR(max_y, hi[1], 1e-9);
  EXPECT_NEAR(min_z, lo[2], 1e-9);
  EXPECT_NEAR(max_z, hi[2], 1e-9);
  EXPECT_DOUBLE_EQ(offset[0], 1000.0);  // the minimum rounded down to the metre
}

// The header's creation day and year are the data's (UTC), not the day the
// file was written: the same log gives the same bytes on any day.
TEST(Las, CreationDayIsTheDayOfTheData) {
  test::TempDir dir;
  MapCloud cloud = test::sampleCloud();
  for (std::size_t i = 0; i < cloud.size(); ++i) cloud.time[i] = 1.7e9 + 3600.0 * i;
  writeLas(dir.file("dated.las"), cloud);
  const Bytes dated = readAll(dir.file("dated.las"));
  EXPECT_EQ(dated.at<std::uint16_t>(90), 318);  // 1.7e9 s: 2023-11-14 22:13:20 UTC
  EXPECT_EQ(dated.at<std::uint16_t>(92), 2023);
  for (std::size_t i = 0; i < cloud.size(); ++i) cloud.time[i] = 12.5 + i;  // since boot
  writeLas(dir.file("undated.las"), cloud);
  const Bytes undated = readAll(dir.file("undated.las"));
  EXPECT_EQ(undated.at<std::uint16_t>(90), 0);
  EXPECT_EQ(undated.at<std::uint16_t>(92), 0);
}

TEST(Las, SubsetAndEmptyFiles) {
  test::TempDir dir;
  const MapCloud cloud = test::sampleCloud(100);
  const std::vector<std::uint32_t> subset{5, 7, 99};
  writeLas(dir.file("subset.las"), cloud, &subset);
  const Bytes f = readAll(dir.file("subset.las"));
  EXPECT_EQ(f.at<std::uint64_t>(247), 3u);
  const std::uint32_t point_offset = f.at<std::uint32_t>(96);
  EXPECT_EQ(f.at<std::int32_t>(point_offset + 2 * 37 + 32), cloud.keyframe[99]);
  const std::vector<std::uint32_t> none;
  writeLas(dir.file("empty.las"), cloud, &none);
  EXPECT_EQ(readAll(dir.file("empty.las")).at<std::uint64_t>(247), 0u);
  // Nothing but the finished files in the folder (no temporaries left).
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 2);
}

}  // namespace
}  // namespace storey
