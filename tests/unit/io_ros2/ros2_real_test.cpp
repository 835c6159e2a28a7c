// Real ROS 2 recordings (../shared/data/real, skipped when absent): nebula's
// VLP-16 (dual return) and VLP-32C rosbag2 sqlite3 bags of VelodyneScan
// packets against the driver's decoded clouds, and an Ouster OS1-64 MCAP
// (zstd chunks, ROS 1 message encoding) with PointCloud2 and Imu.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/log_reader.h"
#include "io/ros2_bag.h"
#include "io/rosbag_reader.h"
#include "io/velodyne/pcap_file.h"
#include "io/velodyne/velodyne_packet.h"
#include "io/velodyne/velodyne_pcap_reader.h"
#include "io/velodyne/velodyne_scan_decoder.h"

namespace storey {
namespace {

std::string realData(const std::string& relative) {
  return std::string(STOREY_REAL_DATA_DIR) + "/" + relative;
}

/// Every VelodyneScan message of the ROS 2 bag `path`.
std::vector<VelodyneScanMessage> readPackets(const std::string& path) {
  auto bag = openRos2Bag(path);
  std::vector<VelodyneScanMessage> out;
  bag->select({});
  while (bag->next()) {
    out.emplace_back();
    bag->readVelodyneScan(out.back());
  }
  return out;
}

TEST(Ros2RealData, Vlp16DualPacketsAreTheCapturesAndDecodeAsIt) {
  const std::string dir = realData("nebula-vlp16-dual");
  if (!std::filesystem::exists(dir + "/rosbag2")) GTEST_SKIP() << "real data absent: " << dir;
  const auto messages = readPackets(dir + "/rosbag2");
  ASSERT_EQ(messages.size(), 4u);
  const std::size_t sizes[] = {151, 151, 151, 150};
  for (int i = 0; i < 4; ++i) EXPECT_EQ(messages[i].packets.size(), sizes[i]);
  // The packets are the capture's (whose decoding test_io_pcap checks point by
  // point against nebula's expected-scan-4.pcd), byte for byte.
  velodyne::PcapFile pcap(dir + "/vlp16-dual-4-scans.pcap");
  velodyne::UdpDatagram d;
  std::size_t n = 0, equal = 0;
  for (const auto& m : messages) {
    for (const auto& p : m.packets) {
      ASSERT_TRUE(pcap.next(d));
      ++n;
      equal += d.size == kVelodynePacketBytes && std::memcmp(d.payload, p.data.data(), d.size) == 0;
    }
  }
  EXPECT_EQ(n, 603u);
  EXPECT_EQ(equal, n);

  // Decoded through the bag reader: the same frames as the capture gives.
  VelodyneScanOptions options;
  options.max_range = 300.0;
  VelodyneScanDecoder decoder("vlp16", options);
  std::vector<Scan> from_bag;
  std::map<std::string, std::int64_t> dropped;
  for (const auto& m : messages) decoder.add(m, from_bag, dropped);
  decoder.flush(from_bag);
  EXPECT_EQ(decoder.model(), velodyne::Model::kVlp16);
  VelodynePcapOptions pcap_options;
  pcap_options.max_range = 300.0;
  pcap_options.require_imu = false;
  pcap_options.drop_scans_beyond_imu = false;
  VelodynePcapReader reader(dir + "/vlp16-dual-4-scans.pcap", pcap_options);
  std::vector<Scan> from_pcap;
  LogMessage message;
  while (reader.next(message)) from_pcap.push_back(std::get<Scan>(message));
  ASSERT_EQ(from_bag.size(), from_pcap.size());
  for (std::size_t i = 0; i < from_bag.size(); ++i) {
    ASSERT_EQ(from_bag[i].points.size(), from_pcap[i].points.size());
    EXPECT_EQ(from_bag[i].stamp_ns, from_pcap[i].stamp_ns);
    for (std::size_t k = 0; k < from_bag[i].points.size(); ++k) {
      ASSERT_EQ(from_bag[i].points[k].p, from_pcap[i].points[k].p);
    }
  }
}

struct Xyz {
  float x, y, z;
};

/// x y z of a binary PCD whose points start with three float32 (`stride` bytes each).
std::vector<Xyz> readXyzPcd(const std::string& path, std::size_t stride = 12) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t points = 0;
  while (std::getline(in, line)) {
    if (line.rfind("POINTS ", 0) == 0) points = std::stoul(line.substr(7));
    if (line.rfind("DATA", 0) == 0) break;
  }
  std::vector<Xyz> out(points);
  std::vector<char> record(stride);
  for (auto& p : out) {
    in.read(record.data(), static_cast<std::streamsize>(stride));
    std::memcpy(&p, record.data(), sizeof(Xyz));
  }
  return in ? out : std::vector<Xyz>{};
}

/// Every kept return of `packets`, in packet order, and the packets' counts summed.
std::vector<velodyne::Return> decodeAll(const velodyne::PacketDecoder& decoder,
                                        const std::vector<VelodynePacketMessage>& packets,
                                        velodyne::PacketCounts* counts = nullptr) {
  std::vector<velodyne::Return> returns;
  velodyne::DataPacket packet;
  for (const auto& p : packets) {
    EXPECT_EQ(decoder.decode(p.data.data(), p.data.size(), packet), velodyne::PacketProblem::kNone);
    returns.insert(returns.end(), packet.returns.begin(), packet.returns.end());
    if (counts != nullptr) counts->outside_window += packet.counts.outside_window;
  }
  return returns;
}

struct PointErrors {
  double max = 0.0, median = 0.0;
};

/// Distances between returns[i] and expected[i] (same order, same count).
PointErrors pointErrors(const std::vector<velodyne::Return>& returns,
                        const std::vector<Xyz>& expected) {
  std::vector<double> d;
  for (std::size_t i = 0; i < std::min(returns.size(), expected.size()); ++i) {
    const auto& r = returns[i];
    const auto& e = expected[i];
    d.push_back(std::hypot(double{r.x} - e.x, double{r.y} - e.y, double{r.z} - e.z));
  }
  if (d.empty()) return {};
  std::sort(d.begin(), d.end());
  return {d.back(), d[d.size() / 2]};
}

// nebula's VLP-16 test settings (tier4/nebula 606ac41, velodyne_ros_decoder_test_vlp16.cpp):
// dual return, VLP16.yaml (the manual's table), min_range 0.3, max_range 300 m,
// cloud_min_angle 0, cloud_max_angle 359, scan_phase 0.
TEST(Ros2RealData, Vlp16DualPacketsDecodeToTheDriversCloud) {
  const std::string dir = realData("nebula-vlp16-dual");
  if (!std::filesystem::exists(dir + "/rosbag2")) GTEST_SKIP() << "real data absent: " << dir;
  const auto messages = readPackets(dir + "/rosbag2");
  ASSERT_EQ(messages.size(), 4u);
  const auto expected = readXyzPcd(dir + "/expected-scan-4.pcd", 32);
  ASSERT_EQ(expected.size(), 14831u);

  velodyne::DecodeOptions options;
  options.azimuth = velodyne::AzimuthInterpolation::kNebula;
  options.min_range = 0.3;
  options.max_range = 300.0;
  options.window = {0.0, 359.0};
  const velodyne::PacketDecoder decoder(velodyne::defaultCalibration(velodyne::Model::kVlp16),
                                        options);
  // nebula's scan cut (scan_phase 0), reproduced here only as far as these
  // messages need it: each message's last packet completes a scan, whose
  // trailing returns below 90 deg (whole degrees) move to the next scan.
  auto trailingBelow90 = [](const std::vector<velodyne::Return>& returns) {
    std::size_t k = returns.size();
    while (k > 0 && std::lround(returns[k - 1].azimuth_deg * 100.0f) / 100 < 90) --k;
    return k;
  };
  const auto previous = decodeAll(decoder, messages[2].packets);
  const auto current = decodeAll(decoder, messages[3].packets);
  std::vector<velodyne::Return> cloud(
      previous.begin() + static_cast<std::ptrdiff_t>(trailingBelow90(previous)), previous.end());
  cloud.insert(cloud.end(), current.begin(),
               current.begin() + static_cast<std::ptrdiff_t>(trailingBelow90(current)));
  const auto errors = pointErrors(cloud, expected);
  std::printf(
      "[ vlp16 ] nebula's arithmetic: %zu returns, %zu expected, max %.4f mm, median "
      "%.5f mm\n",
      cloud.size(), expected.size(), 1e3 * errors.max, 1e3 * errors.median);
  EXPECT_EQ(cloud.size(), expected.size());
  EXPECT_LE(errors.max, 0.002);
}

// nebula's VLP-32 test settings (velodyne_ros_decoder_test_vlp32.cpp): strongest
// return, VLP32.yaml (vert_correction and rot_correction are the VLP-32C manual's
// table, every other correction 0; distance_resolution 0.004 m), min_range 0.4,
// max_range 50 m, cloud_min_angle 270, cloud_max_angle 90, scan_phase 180: the
// first message's last packet completes the scan (its last block wraps back
// to 270 deg), so the cloud is the first message's returns.
TEST(Ros2RealData, Vlp32cPacketsDecodeToTheDriversCloud) {
  const std::string dir = realData("nebula-vlp32c-rosbag2");
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "real data absent: " << dir;
  const auto messages = readPackets(dir + "/rosbag2");
  ASSERT_EQ(messages.size(), 5u);
  const auto expected = readXyzPcd(dir + "/expected-scan-1.pcd");
  ASSERT_EQ(expected.size(), 26216u);
  velodyne::DataPacket first;
  const auto& bytes = messages[0].packets.front().data;
  ASSERT_EQ(velodyne::PacketDecoder(velodyne::defaultCalibration(velodyne::Model::kVlp32c), {})
                .decode(bytes.data(), bytes.size(), first),
            velodyne::PacketProblem::kNone);
  EXPECT_EQ(first.product, velodyne::kProductVlp32c);

  velodyne::DecodeOptions options;
  options.min_range = 0.4;
  options.max_range = 50.0;
  options.window = {270.0, 90.0};
  const auto calibration = velodyne::defaultCalibration(velodyne::Model::kVlp32c);
  // The window is the whole count difference: the last packet's blocks at
  // 90.14 .. 90.95 deg hold 114 returns.
  velodyne::PacketCounts counts;
  const auto manual =
      decodeAll(velodyne::PacketDecoder(calibration, options), messages[0].packets, &counts);
  EXPECT_EQ(manual.size(), expected.size());
  EXPECT_EQ(counts.outside_window, 114);
  // Storey's own azimuth (the manual's: laser pairs fire together, the last
  // block rotates like the others, no rounding) differs from nebula's by up
  // to 5 cm at 24 m (docs/formats.md).
  const auto manual_errors = pointErrors(manual, expected);
  EXPECT_GT(manual_errors.max, 0.04);
  EXPECT_LT(manual_errors.max, 0.05);

  options.azimuth = velodyne::AzimuthInterpolation::kNebula;
  const auto returns =
      decodeAll(velodyne::PacketDecoder(calibration, options), messages[0].packets);
  const auto errors = pointErrors(returns, expected);
  std::printf(
      "[ vlp32c ] %zu expected points; manual azimuth: %zu returns, max %.2f mm, median "
      "%.2f mm; nebula's arithmetic: %zu returns, max %.4f mm, median %.5f mm\n",
      expected.size(), manual.size(), 1e3 * manual_errors.max, 1e3 * manual_errors.median,
      returns.size(), 1e3 * errors.max, 1e3 * errors.median);
  EXPECT_EQ(returns.size(), expected.size());
  EXPECT_LE(errors.max, 0.002);
}

TEST(Ros2RealData, OusterMcapCloudsAndImuReadCorrectly) {
  const std::string file = realData("ouster-os1-64-mcap/os1-64-indoor.mcap");
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "real data absent: " << file;
  auto bag = openRos2Bag(file);
  EXPECT_EQ(bag->formatName(), "MCAP");
  std::int64_t messages = 0;
  for (const auto& t : bag->topics()) messages += t.count;
  EXPECT_EQ(messages, 273);
  bag->select({"/os1_cloud_node/points", "/os1_cloud_node/imu"});
  std::vector<PointCloudMessage> clouds;
  std::vector<ImuMessage> imu;
  while (bag->next()) {
    if (bag->topic() == "/os1_cloud_node/points") {
      clouds.emplace_back();
      bag->readPointCloud(clouds.back());
    } else {
      imu.push_back(bag->readImu());
    }
  }
  ASSERT_EQ(clouds.size(), 2u);
  ASSERT_EQ(imu.size(), 17u);
  for (const auto& c : clouds) {
    EXPECT_EQ(c.height, 64u);
    EXPECT_EQ(c.width, 2048u);
    EXPECT_EQ(c.point_step, 48u);
    EXPECT_EQ(c.data.size(), 64u * 2048u * 48u);
    std::vector<std::string> names;
    for (const auto& f : c.fields) names.push_back(f.name);
    EXPECT_EQ(names, (std::vector<std::string>{"x", "y", "z", "intensity", "t", "reflectivity",
                                               "ring", "noise", "range"}));
  }
  EXPECT_NEAR(clouds[0].stamp_ns * 1e-9, 1588075038.629916, 1e-5);
  EXPECT_NEAR(clouds[1].stamp_ns * 1e-9, 1588075038.729033, 1e-5);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < imu.size(); ++i) {
    if (i > 0) {
      EXPECT_GT(imu[i].sample.stamp_ns, imu[i - 1].sample.stamp_ns);
    }
    mean += imu[i].sample.accel / static_cast<double>(imu.size());
  }
  EXPECT_NEAR(imu.front().sample.stamp_ns * 1e-9, 1622.472294, 1e-5);  // the sensor's own clock
  EXPECT_NEAR(mean.norm(), 9.4, 0.3);
  EXPECT_NEAR(mean.x(), -0.24, 0.2);
  EXPECT_NEAR(mean.y(), 0.78, 0.2);

  // Through the log reader: two scans of the Ouster layout (rings from the
  // bottom, per-point times in [0, 0.1 s)) and the IMU samples.
  SensorConfig sensor;
  sensor.lidar_model = LidarModel::kOs1_64;
  auto reader = openRos2Log(file, InputConfig{}, sensor);
  int scans = 0, samples = 0;
  LogMessage message;
  while (reader->next(message)) {
    if (const auto* scan = std::get_if<Scan>(&message)) {
      ++scans;
      EXPECT_GT(scan->points.size(), 40000u);  // indoors: many no-returns
      const auto span = scan->timeSpan();
      EXPECT_GE(span.first, 0.0);
      EXPECT_LT(span.second, 0.11);
    } else {
      ++samples;
    }
  }
  EXPECT_EQ(scans, 2);
  EXPECT_EQ(samples, 17);
}

}  // namespace
}  // namespace storey
