// PCD files (ascii, binary, binary_compressed) and PCD folder logs: scan
// times from file names or a list file, per-point time fields, IMU CSV
// alongside, detection, errors; the real fast_gicp HDL-32E scans.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "config/config.h"
#include "io/log_format.h"
#include "io/log_reader.h"
#include "io/log_summary.h"
#include "io/pcd_file.h"
#include "io/pcd_folder_reader.h"
#include "real_data.h"

namespace storey {
namespace {

namespace fs = std::filesystem;

struct Field {
  std::string name;
  char type;
  int size;
};

/// Writes a PCD with the given fields and points (one value per field).
void writePcd(const std::string& path, const std::vector<Field>& fields,
              const std::vector<std::vector<double>>& points, const std::string& data) {
  std::ofstream out(path, std::ios::binary);
  out << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS";
  for (const auto& f : fields) out << ' ' << f.name;
  out << "\nSIZE";
  for (const auto& f : fields) out << ' ' << f.size;
  out << "\nTYPE";
  for (const auto& f : fields) out << ' ' << f.type;
  out << "\nCOUNT";
  for (std::size_t i = 0; i < fields.size(); ++i) out << " 1";
  out << "\nWIDTH " << points.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS "
      << points.size() << "\nDATA " << data << "\n";
  auto encode = [](const Field& f, double v, std::vector<std::uint8_t>& bytes) {
    std::uint8_t raw[8];
    if (f.type == 'F' && f.size == 4) {
      float x = static_cast<float>(v);
      std::memcpy(raw, &x, 4);
    } else if (f.type == 'F') {
      std::memcpy(raw, &v, 8);
    } else if (f.type == 'U' && f.size == 1) {
      raw[0] = static_cast<std::uint8_t>(v);
    } else if (f.type == 'U' && f.size == 2) {
      auto x = static_cast<std::uint16_t>(v);
      std::memcpy(raw, &x, 2);
    } else if (f.type == 'U' && f.size == 4) {
      auto x = static_cast<std::uint32_t>(v);
      std::memcpy(raw, &x, 4);
    } else {
      auto x = static_cast<std::uint64_t>(v);
      std::memcpy(raw, &x, 8);
    }
    bytes.insert(bytes.end(), raw, raw + f.size);
  };
  if (data == "ascii") {
    for (const auto& p : points) {
      for (std::size_t i = 0; i < p.size(); ++i) out << (i ? " " : "") << p[i];
      out << '\n';
    }
  } else if (data == "binary") {
    std::vector<std::uint8_t> bytes;
    for (const auto& p : points) {
      for (std::size_t i = 0; i < fields.size(); ++i) encode(fields[i], p[i], bytes);
    }
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
  } else {  // binary_compressed: field-major, LZF with literal runs only
    std::vector<std::uint8_t> soa;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      for (const auto& p : points) encode(fields[i], p[i], soa);
    }
    std::vector<std::uint8_t> lzf;
    for (std::size_t at = 0; at < soa.size(); at += 32) {
      const std::size_t run = std::min<std::size_t>(32, soa.size() - at);
      lzf.push_back(static_cast<std::uint8_t>(run - 1));
      lzf.insert(lzf.end(), soa.begin() + at, soa.begin() + at + run);
    }
    const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(lzf.size()),
                                    static_cast<std::uint32_t>(soa.size())};
    out.write(reinterpret_cast<const char*>(sizes), 8);
    out.write(reinterpret_cast<const char*>(lzf.data()), static_cast<std::streamsize>(lzf.size()));
  }
}

/// A ring-ordered VLP-16-like scan of a 6 m cylinder: 16 rings x 360 points.
std::vector<std::vector<double>> cylinderScan(bool with_time) {
  std::vector<std::vector<double>> points;
  for (int a = 0; a < 360; ++a) {
    for (int ring = 0; ring < 16; ++ring) {
      const double az = -a * M_PI / 180.0;  // clockwise
      const double el = (-15.0 + 2.0 * ring) * M_PI / 180.0;
      const double r = 6.0 / std::cos(el);
      std::vector<double> p = {r * std::cos(el) * std::cos(az), r * std::cos(el) * std::sin(az),
                               r * std::sin(el), 20.0 + ring, static_cast<double>(ring)};
      if (with_time) p.push_back(a * 0.1 / 360.0);
      points.push_back(p);
    }
  }
  return points;
}

class PcdFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("storey_pcd_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void writeImu(const std::string& file, double t0, double t1) const {
    std::ofstream csv(file);
    csv << "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
    for (double t = t0; t <= t1 + 1e-9; t += 0.005) csv << std::fixed << t << ",0,0,0,0,0,9.81\n";
  }
  fs::path dir_;
};

const std::vector<Field> kXyzirt = {{"x", 'F', 4},         {"y", 'F', 4},    {"z", 'F', 4},
                                    {"intensity", 'F', 4}, {"ring", 'U', 2}, {"time", 'F', 4}};

TEST_F(PcdFolder, ThreeEncodingsDecodeToTheSameCloud) {
  const auto scan = cylinderScan(true);
  for (const std::string data : {"ascii", "binary", "binary_compressed"}) {
    const auto file = path("scan_" + data + ".pcd");
    writePcd(file, kXyzirt, scan, data);
    const PcdCloud cloud = readPcd(file);
    ASSERT_EQ(cloud.header.points, scan.size()) << data;
    EXPECT_EQ(cloud.header.point_step, 22u);
    float x;
    std::uint16_t ring;
    std::memcpy(&x, cloud.bytes.data() + 22 * 17, 4);
    std::memcpy(&ring, cloud.bytes.data() + 22 * 17 + 16, 2);
    EXPECT_NEAR(x, scan[17][0], 1e-4) << data;
    EXPECT_EQ(ring, 1) << data;
  }
}

TEST_F(PcdFolder, StampsFromFileNamesAndPointTimesFromTheTimeField) {
  for (int i = 0; i < 3; ++i) {
    char name[64];
    std::snprintf(name, sizeof(name), "%.6f.pcd", 1673400471.5 + 0.1 * i);
    writePcd(path(name), kXyzirt, cylinderScan(true), "binary");
  }
  writeImu(path("imu.csv"), 1673400471.3, 1673400471.9);
  EXPECT_EQ(detectLogFormat(dir_.string()), LogFormat::kPcdFolder);
  const auto reader = openLog(dir_.string(), InputConfig{}, SensorConfig{});
  std::vector<Scan> scans;
  int imu = 0;
  LogMessage m;
  while (reader->next(m)) {
    if (auto* s = std::get_if<Scan>(&m))
      scans.push_back(std::move(*s));
    else
      ++imu;
  }
  ASSERT_EQ(scans.size(), 3u);
  EXPECT_EQ(scans[0].stamp_ns, 1673400471500000000LL);
  EXPECT_EQ(scans[2].stamp_ns, 1673400471700000000LL);
  EXPECT_NEAR(imu, 121, 1);  // 0.6 s at 200 Hz
  EXPECT_EQ(scans[0].points.size(), 16u * 360u);
  EXPECT_NEAR(scans[0].timeSpan().second, 359 * 0.1 / 360.0, 1e-6);
  EXPECT_EQ(scans[0].points[5].ring, 5);
}

TEST_F(PcdFolder, ListFileGivesTimesAndAzimuthGivesPointTimes) {
  const std::vector<Field> xyzi = {
      {"x", 'F', 4}, {"y", 'F', 4}, {"z", 'F', 4}, {"intensity", 'F', 4}};
  auto scan = cylinderScan(false);
  for (auto& p : scan) p.resize(4);
  writePcd(path("a.pcd"), xyzi, scan, "ascii");
  writePcd(path("b.pcd"), xyzi, scan, "binary_compressed");
  std::ofstream(path("timestamps.txt")) << "# file time\na.pcd 100.0\nb.pcd 100.1\n";
  writeImu(path("my_imu.csv"), 99.9, 100.3);
  Config config;
  config.input.imu_csv = path("my_imu.csv");
  const auto reader = openLog(dir_.string(), config.input, config.sensor);
  std::vector<Scan> scans;
  LogMessage m;
  while (reader->next(m)) {
    if (auto* s = std::get_if<Scan>(&m)) scans.push_back(std::move(*s));
  }
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_EQ(scans[1].stamp_ns, 100'100'000'000LL);
  // No time field: times from the azimuth over the scan period (0.1 s here).
  EXPECT_GT(scans[1].timeSpan().second, 0.09f);
  // No ring field: rings from the VLP-16 table, 0 = lowest.
  EXPECT_EQ(scans[1].points[0].ring, 0);
  EXPECT_EQ(scans[1].points[15].ring, 15);
}

TEST_F(PcdFolder, ErrorsNameThePlace) {
  // A folder without scans is not a log.
  EXPECT_THROW(detectLogFormat(dir_.string()), Error);
  // Scan numbers instead of times.
  writePcd(path("000001.pcd"), kXyzirt, cylinderScan(true), "binary");
  writePcd(path("000002.pcd"), kXyzirt, cylinderScan(true), "binary");
  try {
    findPcdScans(dir_.string());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("timestamps.txt"), std::string::npos) << e.what();
  }
  // A truncated body names the file and the byte.
  std::ofstream(path("timestamps.txt")) << "000001.pcd 5.0\n000002.pcd 5.1\n";
  fs::resize_file(path("000002.pcd"), fs::file_size(path("000002.pcd")) - 100);
  writeImu(path("imu.csv"), 4.9, 5.3);
  const auto reader = openLog(dir_.string(), InputConfig{}, SensorConfig{});
  LogMessage m;
  try {
    while (reader->next(m)) {
    }
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("000002.pcd"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  // Without IMU a run is refused, naming the way out.
  fs::remove(path("imu.csv"));
  try {
    openLog(dir_.string(), InputConfig{}, SensorConfig{});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("imu.csv"), std::string::npos) << e.what();
  }
  // A single PCD file is not a log.
  EXPECT_THROW(detectLogFormat(path("000001.pcd")), Error);
}

TEST_F(PcdFolder, AsciiValueBeyondItsFieldTypeIsAnError) {
  // Found by fuzzing (tests/data/fuzz/pcd): -2 in a U 2 field was converted
  // out of range (undefined behaviour); it is an error naming line and field.
  std::ofstream(path("a.pcd")) << "VERSION 0.7\nFIELDS x y z ring\nSIZE 4 4 4 2\nTYPE F F F U\n"
                                  "COUNT 1 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n"
                                  "1 2 3 0\n4 5 6 -2\n";
  try {
    readPcd(path("a.pcd"));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("a.pcd: PCD ascii data line 2: value '-2' of field 'ring'"),
              std::string::npos)
        << what;
  }
  std::ofstream(path("b.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                  "COUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n"
                                  "1e300 nan inf\n";
  EXPECT_THROW(readPcd(path("b.pcd")), Error);  // beyond float; NaN and inf stay allowed
  // Found by the fuzz smoke of CI (tests/data/fuzz/pcd): POINTS -2 wrapped to
  // 2^64 - 2 and the body's allocation threw std::length_error; a header asking
  // for more points than the file can hold is an error before allocating.
  std::ofstream(path("c.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                  "COUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS -2\nDATA binary\n";
  try {
    readPcd(path("c.pcd"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("negative number of points"), std::string::npos)
        << e.what();
  }
  std::ofstream(path("d.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                  "COUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 4000000000000\n"
                                  "DATA binary\n0123456789ab";
  try {
    readPcd(path("d.pcd"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be in the 12 bytes after the header"),
              std::string::npos)
        << e.what();
  }
  // Found by the fuzz smoke of CI (tests/data/fuzz/pcd): an ascii header with a
  // huge COUNT asked for 2.4 GB from a few bytes (the ascii bound was one
  // character a point; here COUNT 4000000 would be 96 MB); every value takes a
  // character and a separator.
  std::ofstream(path("f.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                  "COUNT 1 1 4000000\nWIDTH 6\nHEIGHT 1\nPOINTS 6\n"
                                  "DATA ascii\n1 2 3\n4 5 6\n";
  try {
    readPcd(path("f.pcd"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be in the 12 bytes after the header"),
              std::string::npos)
        << e.what();
  }
  // COUNT 2000000000 of 8-byte values wrapped the 32-bit point step.
  std::ofstream(path("g.pcd")) << "VERSION 0.7\nFIELDS x y\nSIZE 8 8\nTYPE F F\n"
                                  "COUNT 1 2000000000\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
                                  "DATA binary\n0123456789ab";
  try {
    readPcd(path("g.pcd"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at most 16 MiB a point"), std::string::npos) << e.what();
  }
  // An ordinary ascii cloud still reads.
  std::ofstream(path("h.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                  "COUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n"
                                  "DATA ascii\n1 2 3\n4 5 6";
  EXPECT_EQ(readPcd(path("h.pcd")).header.points, 2u);
  // WIDTH -1 wrapped to 2^32 - 1 through stoul; a negative or > 32-bit count is an error.
  for (const char* width : {"-1", "4294967296"}) {
    std::ofstream(path("e.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                    "COUNT 1 1 1\nWIDTH "
                                 << width << "\nHEIGHT 1\nPOINTS 1\nDATA binary\n0123456789ab";
    try {
      readPcd(path("e.pcd"));
      FAIL() << "no error for WIDTH " << width;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("WIDTH must be a count of points"), std::string::npos)
          << e.what();
    }
  }
}

TEST_F(PcdFolder, FileNameStampUnits) {
  std::int64_t ns = 0;
  ASSERT_TRUE(stampFromFileName("scan_1673400471.25.pcd", ns));
  EXPECT_EQ(ns, 1673400471250000000LL);
  ASSERT_TRUE(stampFromFileName("1673400471250000000.pcd", ns));
  EXPECT_EQ(ns, 1673400471250000000LL);
  ASSERT_TRUE(stampFromFileName("1673400471250000.pcd", ns));
  EXPECT_EQ(ns, 1673400471250000000LL);
  ASSERT_TRUE(stampFromFileName("1673400471250.pcd", ns));
  EXPECT_EQ(ns, 1673400471250000000LL);
  ASSERT_TRUE(stampFromFileName("1673400471.pcd", ns));
  EXPECT_EQ(ns, 1673400471000000000LL);
  EXPECT_FALSE(stampFromFileName("scan.pcd", ns));
}

TEST_F(PcdFolder, RealHdl32eScans) {
  const std::string src = test::realData("fast_gicp-scan-pair");
  if (!fs::exists(src)) GTEST_SKIP() << "real data absent: " << src;
  fs::copy_file(src + "/251370668.pcd", path("251370668.pcd"));
  fs::copy_file(src + "/251371071.pcd", path("251371071.pcd"));
  // Their names are not times: list them (0.1 s apart, as an HDL-32E at 10 Hz).
  std::ofstream(path("timestamps.txt")) << "251370668.pcd 10.0\n251371071.pcd 10.1\n";
  writeImu(path("imu.csv"), 9.9, 10.3);
  Config config;
  config.sensor.lidar_model = LidarModel::kHdl32e;
  const LogSummary summary = summarizeLog(dir_.string(), config.input, config.sensor);
  EXPECT_EQ(summary.format, "PCD folder");
  ASSERT_EQ(summary.topics.size(), 2u);
  EXPECT_EQ(summary.topics[0].count, 2);
  EXPECT_TRUE(summary.input_problem.empty()) << summary.input_problem;
  const auto reader = openLog(dir_.string(), config.input, config.sensor);
  std::vector<Scan> scans;
  LogMessage m;
  while (reader->next(m)) {
    if (auto* s = std::get_if<Scan>(&m)) scans.push_back(std::move(*s));
  }
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_GT(scans[0].points.size(), 50000u);  // of 69088, invalid and out-of-range points dropped
  std::uint16_t max_ring = 0;
  for (const auto& p : scans[0].points) max_ring = std::max(max_ring, p.ring);
  EXPECT_EQ(max_ring, 31);
}

}  // namespace
}  // namespace storey
