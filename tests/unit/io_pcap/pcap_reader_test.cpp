// The Velodyne pcap reader on synthetic captures: frames, per-point times,
// rotation rate, dual return, and bad input (truncated packets, foreign
// traffic, a file cut in a record, packets out of order, nothing usable).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

#include "common/error.h"
#include "config/config.h"
#include "io/log_format.h"
#include "io/log_reader.h"
#include "io/log_summary.h"
#include "io/velodyne/frame_assembler.h"
#include "io/velodyne/velodyne_packet.h"
#include "io/velodyne/velodyne_pcap_reader.h"
#include "pcap_fixtures.h"

namespace storey {
namespace {

namespace fs = std::filesystem;
using test::PcapRecord;

class PcapReader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("storey_pcap_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  struct Read {
    std::vector<Scan> scans;
    std::vector<ImuSample> imu;
    LogReadStats stats;
    double rotation_hz = 0.0;
  };
  static Read readAll(const std::string& path, VelodynePcapOptions options = noImu()) {
    VelodynePcapReader reader(path, options);
    Read out;
    LogMessage m;
    while (reader.next(m)) {
      if (auto* s = std::get_if<Scan>(&m))
        out.scans.push_back(std::move(*s));
      else
        out.imu.push_back(std::get<ImuSample>(m));
    }
    out.stats = reader.stats();
    out.rotation_hz = reader.rotationHz();
    return out;
  }
  static VelodynePcapOptions noImu() {
    VelodynePcapOptions o;
    o.require_imu = false;
    return o;
  }
  static std::int64_t dropped(const Read& r, const std::string& key) {
    const auto it = r.stats.dropped.find(key);
    return it == r.stats.dropped.end() ? 0 : it->second;
  }

  fs::path dir_;
};

TEST_F(PcapReader, CleanCaptureIsCutIntoRevolutionsWithFiringTimes) {
  // 0.45 s at 10 Hz starting at azimuth 90 deg: a partial first frame (3/4
  // turn), three full ones and a partial last one.
  const auto records = test::vlp16Capture(0.45, 10.0, 1'000'000, 9000);
  ASSERT_GT(records.size(), 250u);
  test::writePcap(file("clean.pcap"), records);
  EXPECT_EQ(detectLogFormat(file("clean.pcap")), LogFormat::kVelodynePcap);
  const Read r = readAll(file("clean.pcap"));
  ASSERT_EQ(r.scans.size(), 5u);
  EXPECT_NEAR(r.rotation_hz, 10.0, 0.05);
  // Full frames: 16 lasers x 2 sequences x 12 blocks per packet, ~75.4 packets per turn.
  for (int f = 1; f <= 3; ++f) {
    EXPECT_NEAR(static_cast<double>(r.scans[f].points.size()), 0.1 / 1327.104e-6 * 384, 400) << f;
    EXPECT_NEAR(nsToSeconds(r.scans[f + 1].stamp_ns - r.scans[f].stamp_ns), 0.1, 0.001);
  }
  // The first frame covers 90..360 deg: three quarters of a turn.
  EXPECT_NEAR(static_cast<double>(r.scans[0].points.size()) / r.scans[1].points.size(), 0.75, 0.02);
  // Every point is 5 m away, its ring 0..15 ordered by elevation, times in
  // firing order: laser k of sequence s of block b at b*110.592 + s*55.296 + k*2.304 us.
  const Scan& scan = r.scans[1];
  for (const auto& p : scan.points) {
    ASSERT_NEAR(p.p.norm(), 5.0, 1e-3);
    ASSERT_LT(p.ring, 16);
  }
  EXPECT_FLOAT_EQ(scan.points[0].time, 0.0f);
  EXPECT_NEAR(scan.points[1].time, 2.304e-6, 1e-9);     // laser 1
  EXPECT_NEAR(scan.points[16].time, 55.296e-6, 1e-9);   // sequence 2, laser 0
  EXPECT_NEAR(scan.points[32].time, 110.592e-6, 1e-9);  // block 1
  for (std::size_t i = 1; i < scan.points.size(); ++i)
    ASSERT_GE(scan.points[i].time, scan.points[i - 1].time);
  // Ring 0 is the lowest laser (-15 deg), ring 15 the highest.
  for (const auto& p : scan.points) {
    const double elevation = std::asin(p.p.z() / p.p.norm()) * 180.0 / M_PI;
    ASSERT_NEAR(elevation, -15.0 + 2.0 * p.ring, 1e-3);
  }
  // Azimuth 0 is +x and the head turns clockwise: a quarter turn later points are at -y.
  EXPECT_EQ(dropped(r, kDropNotVelodyne), 0);
}

TEST(VelodyneFrameCut, StartsWhereTheHeadPassesTheCutAzimuth) {
  using velodyne::startsFrame;
  // Cut 0 (the default): exactly where the azimuth decreases (VeloView's rule),
  // 36000 (sent for 0 by some firmware) not counting as a wrap until it drops.
  for (const auto& [previous, azimuth] :
       std::vector<std::pair<int, int>>{{35990, 10}, {36000, 5}, {100, 90}, {20000, 0}}) {
    EXPECT_TRUE(startsFrame(previous, azimuth, 0)) << previous << " -> " << azimuth;
  }
  for (const auto& [previous, azimuth] :
       std::vector<std::pair<int, int>>{{0, 20}, {35990, 36000}, {17990, 18010}, {50, 50}}) {
    EXPECT_FALSE(startsFrame(previous, azimuth, 0)) << previous << " -> " << azimuth;
  }
  // Cut 180 deg: the block at or just past 18000.
  EXPECT_TRUE(startsFrame(17990, 18000, 18000));
  EXPECT_TRUE(startsFrame(17980, 18010, 18000));
  EXPECT_FALSE(startsFrame(18000, 18020, 18000));
  EXPECT_FALSE(startsFrame(17960, 17990, 18000));
  EXPECT_FALSE(startsFrame(35990, 10, 18000)) << "a wrap through 0 is no cut at 180 deg";
  // A cut just below 360 deg, passed in the step through 0 deg.
  EXPECT_TRUE(startsFrame(35990, 10, 35995));
  EXPECT_TRUE(startsFrame(35990, 10, 5));
  EXPECT_FALSE(startsFrame(35990, 10, 20));
  EXPECT_EQ(velodyne::cutAzimuth(0.0), 0);
  EXPECT_EQ(velodyne::cutAzimuth(180.0), 18000);
  EXPECT_EQ(velodyne::cutAzimuth(90.004), 9000);
  EXPECT_EQ(velodyne::cutAzimuth(359.999), 0);
}

TEST_F(PcapReader, CutAngleStartsEveryFrameAtThatAzimuth) {
  // The capture of the test above (from azimuth 90 deg), cut at 90 deg: full
  // revolutions from the first packet on, each starting at 90 deg.
  const auto records = test::vlp16Capture(0.45, 10.0, 1'000'000, 9000);
  test::writePcap(file("clean.pcap"), records);
  VelodynePcapOptions options = noImu();
  options.cut_angle_deg = 90.0;
  const Read r = readAll(file("clean.pcap"), options);
  const Read wrap = readAll(file("clean.pcap"));
  ASSERT_EQ(r.scans.size(), 5u);
  EXPECT_EQ(r.scans[0].stamp_ns, wrap.scans[0].stamp_ns) << "the capture's first block";
  std::size_t points = 0, wrap_points = 0;
  for (const Scan& s : r.scans) points += s.points.size();
  for (const Scan& s : wrap.scans) wrap_points += s.points.size();
  EXPECT_EQ(points, wrap_points) << "the same returns, cut elsewhere";
  for (std::size_t f = 0; f < r.scans.size(); ++f) {
    const Eigen::Vector3f& p = r.scans[f].points.front().p;
    // Clockwise from +x: azimuth 90 deg is -y. The first block at or past
    // 90 deg; a block turns the head by 0.398 deg.
    const double azimuth = std::atan2(-p.y(), p.x()) * 180.0 / M_PI;
    EXPECT_GE(azimuth, 90.0 - 0.01) << f;
    EXPECT_LT(azimuth, 90.0 + 0.4) << f;
    if (f + 1 < 4) {
      EXPECT_NEAR(nsToSeconds(r.scans[f + 1].stamp_ns - r.scans[f].stamp_ns), 0.1, 0.0002) << f;
      EXPECT_NEAR(static_cast<double>(r.scans[f].points.size()), 0.1 / 1327.104e-6 * 384, 400);
    }
  }
  // The configuration key reaches the reader.
  Config config;
  config.input.velodyne_cut_angle_deg = 90.0;
  EXPECT_EQ(velodynePcapOptions(config.input, config.sensor).cut_angle_deg, 90.0);
}

TEST_F(PcapReader, SensorClockUnwrapsTheHour) {
  // Timestamps count microseconds past the hour: start 0.15 s before the wrap.
  const auto records = test::vlp16Capture(0.3, 10.0, 3'600'000'000u - 150'000);
  test::writePcap(file("wrap.pcap"), records);
  const Read r = readAll(file("wrap.pcap"));
  ASSERT_GE(r.scans.size(), 3u);
  for (std::size_t i = 1; i < r.scans.size(); ++i) {
    EXPECT_GT(r.scans[i].stamp_ns, r.scans[i - 1].stamp_ns);
    EXPECT_LT(r.scans[i].stamp_ns - r.scans[i - 1].stamp_ns, 110'000'000);
  }
  EXPECT_EQ(dropped(r, kDropPacketLate), 0);
}

TEST_F(PcapReader, ForeignTrafficIsSkippedAndCounted) {
  auto records = test::vlp16Capture(0.25, 10.0, 1'000'000);
  const Read clean = [&] {
    test::writePcap(file("clean.pcap"), records);
    return readAll(file("clean.pcap"));
  }();
  std::vector<PcapRecord> mixed;
  for (std::size_t i = 0; i < records.size(); ++i) {
    mixed.push_back(records[i]);
    if (i % 10 == 0) {
      mixed.push_back(
          {records[i].t_ns, test::udpFrame(5353, 53, std::vector<std::uint8_t>(40, 7)), 0});
      mixed.push_back({records[i].t_ns, test::tcpFrame(), 0});
      mixed.push_back({records[i].t_ns, test::arpFrame(), 0});
      // A 1206-byte payload on another port is not Velodyne data either.
      mixed.push_back(
          {records[i].t_ns, test::udpFrame(9000, 9000, std::vector<std::uint8_t>(1206, 1)), 0});
    }
  }
  test::writePcap(file("mixed.pcap"), mixed);
  const Read r = readAll(file("mixed.pcap"));
  ASSERT_EQ(r.scans.size(), clean.scans.size());
  for (std::size_t i = 0; i < r.scans.size(); ++i)
    EXPECT_EQ(r.scans[i].points.size(), clean.scans[i].points.size());
  const std::int64_t n = static_cast<std::int64_t>((records.size() + 9) / 10);
  EXPECT_EQ(dropped(r, kDropNotVelodyne), 2 * n);
  EXPECT_EQ(dropped(r, "pcap_record_not_udp"), n);
  EXPECT_EQ(dropped(r, "pcap_record_not_ip"), n);
}

TEST_F(PcapReader, TruncatedAndMalformedPacketsAreSkipped) {
  auto records = test::vlp16Capture(0.25, 10.0, 1'000'000);
  // Record 20 captured with only 600 of its bytes (snap length).
  records[20].original_length = static_cast<std::uint32_t>(records[20].frame.size());
  records[20].frame.resize(600);
  // Record 40: a block flag broken.
  records[40].frame[42 + 500] = 0x00;
  // Record 60: a 1000-byte datagram on the data port.
  records[60].frame = test::udpFrame(2368, 2368, std::vector<std::uint8_t>(1000, 0xFF));
  test::writePcap(file("bad.pcap"), records);
  const Read r = readAll(file("bad.pcap"));
  EXPECT_EQ(dropped(r, kDropPacketTruncated), 2);  // the snapped record and the short datagram
  EXPECT_EQ(dropped(r, velodyne::toString(velodyne::PacketProblem::kBadBlockFlag)), 1);
  EXPECT_GE(r.scans.size(), 2u);
}

TEST_F(PcapReader, FileCutInARecordKeepsWhatWasRead) {
  const auto records = test::vlp16Capture(0.25, 10.0, 1'000'000);
  test::writePcap(file("whole.pcap"), records);
  const Read whole = readAll(file("whole.pcap"));
  const auto size = fs::file_size(file("whole.pcap"));
  fs::copy_file(file("whole.pcap"), file("cut.pcap"));
  fs::resize_file(file("cut.pcap"), size - 700);  // in the middle of the last record
  const Read r = readAll(file("cut.pcap"));
  EXPECT_EQ(dropped(r, "pcap_file_cut_in_record"), 1);
  ASSERT_EQ(r.scans.size(), whole.scans.size());
  EXPECT_EQ(r.scans.back().points.size() + 384, whole.scans.back().points.size());
}

TEST_F(PcapReader, OutOfOrderPacketsAreReorderedOrDropped) {
  auto records = test::vlp16Capture(0.25, 10.0, 1'000'000);
  test::writePcap(file("ordered.pcap"), records);
  const Read ordered = readAll(file("ordered.pcap"));
  std::swap(records[30], records[31]);                // reordered within the buffer
  records.insert(records.begin() + 50, records[49]);  // a duplicate
  auto late = records[60];
  records.erase(records.begin() + 60);
  records.insert(records.begin() + 160, late);  // 100 packets late: beyond the buffer
  test::writePcap(file("shuffled.pcap"), records);
  const Read r = readAll(file("shuffled.pcap"));
  EXPECT_EQ(dropped(r, kReorderedPackets), 1);
  EXPECT_EQ(dropped(r, kDropPacketDuplicate), 1);
  EXPECT_EQ(dropped(r, kDropPacketLate), 1);
  ASSERT_EQ(r.scans.size(), ordered.scans.size());
  std::size_t total = 0, total_ordered = 0;
  for (std::size_t i = 0; i < r.scans.size(); ++i) {
    total += r.scans[i].points.size();
    total_ordered += ordered.scans[i].points.size();
    EXPECT_EQ(r.scans[i].stamp_ns, ordered.scans[i].stamp_ns);
    for (std::size_t k = 1; k < r.scans[i].points.size(); ++k) {
      ASSERT_GE(r.scans[i].points[k].time, r.scans[i].points[k - 1].time);
    }
  }
  EXPECT_EQ(total + 384, total_ordered);  // only the late packet's points are missing
}

TEST_F(PcapReader, NothingUsableIsAClearError) {
  std::vector<PcapRecord> records;
  for (int i = 0; i < 20; ++i) {
    records.push_back({1'600'000'000'000'000'000LL + i * 1'000'000,
                       test::udpFrame(5353, 53, std::vector<std::uint8_t>(40, 1)), 0});
  }
  test::writePcap(file("dns.pcap"), records);
  try {
    VelodynePcapReader reader(file("dns.pcap"), noImu());
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file("dns.pcap")), std::string::npos) << what;
    EXPECT_NE(what.find("no Velodyne data packet"), std::string::npos) << what;
    EXPECT_NE(what.find("20 on port 53"), std::string::npos) << what;
  }
  test::writePcap(file("empty.pcap"), {});
  EXPECT_THROW(VelodynePcapReader(file("empty.pcap"), noImu()), Error);
  // A file cut inside its 24-byte header.
  {
    std::ofstream out(file("stub.pcap"), std::ios::binary);
    const unsigned char magic[] = {0xD4, 0xC3, 0xB2, 0xA1, 2, 0, 4, 0};
    out.write(reinterpret_cast<const char*>(magic), sizeof(magic));
  }
  EXPECT_THROW(detectLogFormat(file("stub.pcap")), Error);
  // A capture without IMU cannot be run on: the error names the way out.
  test::writePcap(file("noimu.pcap"), test::vlp16Capture(0.1, 10.0, 1'000'000));
  try {
    openLog(file("noimu.pcap"), InputConfig{}, SensorConfig{});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("imu_csv"), std::string::npos) << e.what();
  }
}

TEST_F(PcapReader, DualReturnPairsShareTheirFiringTime) {
  velodyne::PacketDecoder decoder(velodyne::defaultCalibration(velodyne::Model::kVlp16), {});
  velodyne::DataPacket packet;
  // Second returns 7 m (distinct) then 5 m (identical to the first: dropped).
  for (const double second : {7.0, 5.0}) {
    const auto bytes = test::vlp16Packet(1000, 100, 40, 5.0, true, second);
    ASSERT_EQ(decoder.decode(bytes.data(), bytes.size(), packet), velodyne::PacketProblem::kNone);
    ASSERT_TRUE(packet.dual());
    if (second == 5.0) {
      EXPECT_EQ(packet.returns.size(), 6u * 32u);
      EXPECT_EQ(packet.counts.identical_second, 6 * 32);
      continue;
    }
    ASSERT_EQ(packet.returns.size(), 12u * 32u);
    for (std::size_t i = 0; i < 32; ++i) {
      const auto& first = packet.returns[i + 2 * 32];  // block 2 (pair 1)
      const auto& other = packet.returns[i + 3 * 32];  // block 3 (pair 1)
      EXPECT_FALSE(first.second_return);
      EXPECT_TRUE(other.second_return);
      EXPECT_DOUBLE_EQ(first.time_offset_s, other.time_offset_s);
      EXPECT_NEAR(first.time_offset_s, 110.592e-6 + (i / 16) * 55.296e-6 + (i % 16) * 2.304e-6,
                  1e-12);
      EXPECT_FLOAT_EQ(first.azimuth_deg, other.azimuth_deg);
      EXPECT_NEAR(other.distance, 7.0, 1e-3);
    }
  }
}

/// VLP-32C packets (product id 0x28): one firing sequence per block, laser
/// pairs every 2.304 us, 4 mm distance steps, the manual's uneven table with
/// its azimuth offsets.
TEST_F(PcapReader, Vlp32cPacketsUseItsTableTimingAndDistanceStep) {
  const velodyne::Calibration table = velodyne::defaultCalibration(velodyne::Model::kVlp32c);
  const velodyne::PacketDecoder decoder(table, {});
  auto bytes = test::vlp16Packet(1000, 1000, 20, 5.0);  // every channel: 2500 steps
  bytes[1205] = velodyne::kProductVlp32c;
  velodyne::DataPacket packet;
  ASSERT_EQ(decoder.decode(bytes.data(), bytes.size(), packet), velodyne::PacketProblem::kNone);
  ASSERT_EQ(packet.returns.size(), 12u * 32u);
  for (const velodyne::Return& r : packet.returns) {
    ASSERT_EQ(r.sequence, 0);
    EXPECT_NEAR(r.distance, 2500 * 0.004, 1e-5);
    EXPECT_NEAR(r.time_offset_s, r.block * 55.296e-6 + (r.laser / 2) * 2.304e-6, 1e-12);
    const velodyne::Laser& laser = table.lasers[r.laser];
    EXPECT_NEAR(std::asin(r.z / r.distance) * 180 / M_PI, laser.elevation_deg, 1e-4);
    // Block azimuth, the rotation until the pair fired (0.2 deg per block), the offset.
    const double azimuth = (1000 + 20 * r.block) * 0.01 + 0.2 * ((r.laser / 2) * 2.304 / 55.296) -
                           laser.azimuth_offset_deg;
    EXPECT_NEAR(r.azimuth_deg, azimuth, 1e-4);
  }
  EXPECT_NEAR(table.lasers[0].elevation_deg, -25.0, 1e-12);
  EXPECT_NEAR(table.lasers[0].azimuth_offset_deg, -1.4, 1e-12);  // VeloView's rotCorrection

  // The reader tells the model from the product id.
  auto records = test::vlp16Capture(0.25, 10.0, 1'000'000);
  for (PcapRecord& record : records) record.frame[42 + 1205] = velodyne::kProductVlp32c;
  test::writePcap(file("vlp32c.pcap"), records);
  VelodynePcapReader reader(file("vlp32c.pcap"), noImu());
  EXPECT_EQ(reader.probe().model, velodyne::Model::kVlp32c);
  const Read r = readAll(file("vlp32c.pcap"));
  ASSERT_FALSE(r.scans.empty());
  std::uint16_t max_ring = 0;
  for (const ScanPoint& p : r.scans[1].points) {
    ASSERT_NEAR(p.p.norm(), 10.0, 1e-3);
    max_ring = std::max(max_ring, p.ring);
  }
  EXPECT_EQ(max_ring, 31);
}

TEST_F(PcapReader, ImuCsvIsMergedInTimeOrder) {
  const auto records = test::vlp16Capture(0.35, 10.0, 1'000'000);
  test::writePcap(file("lidar.pcap"), records);
  // Find the sensor clock's first scan time, then write an IMU CSV on a clock
  // 100 s behind, at 200 Hz, covering the capture.
  const Read lidar = readAll(file("lidar.pcap"));
  ASSERT_FALSE(lidar.scans.empty());
  const std::int64_t start_ns = lidar.scans.front().stamp_ns - 100'000'000'000LL - 200'000'000;
  {
    std::ofstream csv(file("imu.csv"));
    csv << "# written by the test\ntime,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
    for (int i = 0; i < 200; ++i) {
      const std::int64_t t = start_ns + i * 5'000'000LL;
      csv << t / 1'000'000'000 << '.' << std::setw(9) << std::setfill('0') << t % 1'000'000'000
          << ",0.01,0,0,0,0,9.81\n";
    }
  }
  VelodynePcapOptions options;
  options.imu_csv = file("imu.csv");
  options.imu_csv_offset_ns = 100'000'000'000LL;
  const Read r = readAll(file("lidar.pcap"), options);
  EXPECT_EQ(r.scans.size(), lidar.scans.size());
  EXPECT_EQ(r.imu.size(), 200u);
  EXPECT_EQ(r.imu.front().stamp_ns, start_ns + 100'000'000'000LL);
  // Delivered in time order: every IMU sample before a scan has an earlier stamp.
  VelodynePcapReader reader(file("lidar.pcap"), options);
  LogMessage m;
  std::int64_t last = 0;
  while (reader.next(m)) {
    const std::int64_t t = std::holds_alternative<Scan>(m) ? std::get<Scan>(m).stamp_ns
                                                           : std::get<ImuSample>(m).stamp_ns;
    EXPECT_GE(t, last);
    last = t;
  }
}

TEST_F(PcapReader, SummaryNamesSensorRateAndDrops) {
  auto records = test::vlp16Capture(0.25, 10.0, 1'000'000);
  records.push_back(
      {records.back().t_ns, test::udpFrame(5353, 53, std::vector<std::uint8_t>(40, 7)), 0});
  test::writePcap(file("s.pcap"), records);
  const LogSummary s = summarizeLog(file("s.pcap"), InputConfig{}, SensorConfig{});
  EXPECT_EQ(s.format, "Velodyne pcap");
  ASSERT_FALSE(s.topics.empty());
  EXPECT_EQ(s.topics.front().type, "scan");
  EXPECT_GE(s.topics.front().count, 3);
  EXPECT_EQ(s.dropped.at(kDropNotVelodyne), 1);
  bool saw_rotation = false;
  for (const auto& [k, v] : s.properties)
    saw_rotation = saw_rotation || (k == "rotation" && v.rfind("10.0", 0) == 0);
  EXPECT_TRUE(saw_rotation);
  EXPECT_FALSE(s.input_problem.empty());  // no IMU
}

}  // namespace
}  // namespace storey
