// IMU CSV: columns, units, time bases, offset, bad lines, errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/imu_csv.h"

namespace storey {
namespace {

namespace fs = std::filesystem;

std::string writeFile(const std::string& name, const std::string& text) {
  const auto path = (fs::temp_directory_path() / ("storey_imu_csv_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

std::vector<ImuSample> readAll(ImuCsvReader& reader) {
  std::vector<ImuSample> out;
  ImuSample s;
  while (reader.next(s)) out.push_back(s);
  return out;
}

TEST(ImuCsv, SecondsAreReadExactlyToTheNanosecond) {
  std::int64_t ns = 0;
  ASSERT_TRUE(parseSecondsToNs("1673400471.737763123", ns));
  EXPECT_EQ(ns, 1673400471737763123LL);
  ASSERT_TRUE(parseSecondsToNs("12", ns));
  EXPECT_EQ(ns, 12'000'000'000LL);
  ASSERT_TRUE(parseSecondsToNs("-0.5", ns));
  EXPECT_EQ(ns, -500'000'000LL);
  EXPECT_FALSE(parseSecondsToNs("1e9", ns));
  EXPECT_FALSE(parseSecondsToNs("abc", ns));
  EXPECT_FALSE(parseSecondsToNs("", ns));
  // Found by fuzzing (tests/data/fuzz/imu_csv): 17e9 s passed the old bound
  // and overflowed int64 nanoseconds (undefined behaviour). The range ends
  // about 292 years after 1970.
  EXPECT_FALSE(parseSecondsToNs("17000000000.0075", ns));
  EXPECT_FALSE(parseSecondsToNs("9223372036.0", ns));
  ASSERT_TRUE(parseSecondsToNs("9223372035.999999999", ns));
  EXPECT_EQ(ns, 9'223'372'035'999'999'999LL);
  // With the offset beyond the range, the line is bad, not wrapped around.
  const auto path = writeFile("edge.csv", "9223372035.9,0,0,0,0,0,9.8\n1,0,0,0,0,0,9.8\n");
  ImuCsvReader reader(path, 1'000'000'000);
  ImuSample sample;
  ASSERT_TRUE(reader.next(sample));
  EXPECT_EQ(sample.stamp_ns, 2'000'000'000LL);
  EXPECT_EQ(reader.badLines(), 1);
}

TEST(ImuCsv, DefaultColumnsWithoutHeader) {
  const auto path = writeFile("plain.csv",
                              "# comment\n"
                              "1673400471.000000,0.1,0.2,0.3,1,2,9.81\n"
                              "\n"
                              "1673400471.005 0.1 0.2 0.3 1 2 9.81\n");
  ImuCsvReader reader(path, 0);
  const auto s = readAll(reader);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].stamp_ns, 1673400471000000000LL);
  EXPECT_EQ(s[1].stamp_ns, 1673400471005000000LL);
  EXPECT_DOUBLE_EQ(s[0].gyro.z(), 0.3);
  EXPECT_DOUBLE_EQ(s[1].accel.z(), 9.81);
}

TEST(ImuCsv, HeaderNamesOrderUnitsAndOffset) {
  const auto path = writeFile("header.csv",
                              "accel_x_g;accel_y_g;accel_z_g;gyro_x_dps;gyro_y_dps;gyro_z_dps;stamp_ns\n"
                              "0;0;1;90;0;0;1000000000\n");
  ImuCsvReader reader(path, 250);
  const auto s = readAll(reader);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].stamp_ns, 1'000'000'250LL);
  EXPECT_NEAR(s[0].gyro.x(), M_PI / 2, 1e-12);
  EXPECT_NEAR(s[0].accel.z(), 9.80665, 1e-12);
}

TEST(ImuCsv, BadLinesAreSkippedAndCounted) {
  const auto path = writeFile("bad.csv",
                              "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n"
                              "1.0,0,0,0,0,0,9.8\n"
                              "1.005,0,0\n"
                              "1.010,0,zero,0,0,0,9.8\n"
                              "1.015,0,0,0,0,0,9.8\n");
  ImuCsvReader reader(path, 0);
  const auto s = readAll(reader);
  EXPECT_EQ(s.size(), 2u);
  EXPECT_EQ(reader.badLines(), 2);
}

TEST(ImuCsv, ErrorsNameTheFile) {
  const auto missing = (fs::temp_directory_path() / "storey_imu_csv_missing.csv").string();
  fs::remove(missing);
  EXPECT_THROW(ImuCsvReader(missing, 0), Error);
  const auto header_only = writeFile("header_only.csv", "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n");
  EXPECT_THROW(ImuCsvReader(header_only, 0), Error);
  const auto wrong = writeFile("wrong.csv", "time,wx,wy,wz,pressure\n1,0,0,0,0\n");
  try {
    ImuCsvReader reader(wrong, 0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(wrong), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("accel_x"), std::string::npos);
  }
}

}  // namespace
}  // namespace storey
