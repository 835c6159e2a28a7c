// Real ROS 2 recordings (../shared/data/real, skipped when absent): nebula's
// VLP-16 (dual return) and VLP-32C rosbag2 sqlite3 bags of VelodyneScan
// packets against the driver's decoded clouds, and an Ouster OS1-64 MCAP
// (zstd chunks, ROS 1 message encoding) with PointCloud2 and Imu.
#include <gtest/gtest.h>

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

std::vector<VelodyneScanMessage> readPackets(RosMessageSource& bag) {
  std::vector<VelodyneScanMessage> out;
  bag.select({});
  while (bag.next()) {
    out.emplace_back();
    bag.readVelodyneScan(out.back());
  }
  return out;
}

TEST(Ros2RealData, Vlp16DualPacketsAreTheCapturesAndDecodeAsIt) {
  const std::string dir = realData("nebula-vlp16-dual");
  if (!std::filesystem::exists(dir + "/rosbag2")) GTEST_SKIP() << "real data absent: " << dir;
  auto bag = openRos2Bag(dir + "/rosbag2");
  const auto messages = readPackets(*bag);
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

std::vector<Xyz> readXyzPcd(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t points = 0;
  while (std::getline(in, line)) {
    if (line.rfind("POINTS ", 0) == 0) points = std::stoul(line.substr(7));
    if (line.rfind("DATA", 0) == 0) break;
  }
  std::vector<Xyz> out(points);
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(points * 12));
  return in ? out : std::vector<Xyz>{};
}

TEST(Ros2RealData, Vlp32cPacketsDecodeToTheDriversCloud) {
  const std::string dir = realData("nebula-vlp32c-rosbag2");
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "real data absent: " << dir;
  auto bag = openRos2Bag(dir + "/rosbag2");
  const auto messages = readPackets(*bag);
  ASSERT_EQ(messages.size(), 5u);
  const auto expected = readXyzPcd(dir + "/expected-scan-1.pcd");
  ASSERT_EQ(expected.size(), 26216u);

  // Every return of the first message's packets (the driver's cloud of that message).
  velodyne::DecodeOptions options;
  options.max_range = 300.0;
  velodyne::PacketDecoder decoder(velodyne::defaultCalibration(velodyne::Model::kVlp32c), options);
  std::vector<velodyne::Return> returns;
  velodyne::DataPacket packet;
  for (const auto& p : messages[0].packets) {
    ASSERT_EQ(decoder.decode(p.data.data(), p.data.size(), packet), velodyne::PacketProblem::kNone);
    EXPECT_EQ(packet.product, velodyne::kProductVlp32c);
    returns.insert(returns.end(), packet.returns.begin(), packet.returns.end());
  }
  // Nearest decoded return of each expected point (grid of 0.1 m cells).
  std::map<std::tuple<int, int, int>, std::vector<std::size_t>> grid;
  auto cell = [](double x, double y, double z) {
    return std::make_tuple(static_cast<int>(std::floor(x * 10)),
                           static_cast<int>(std::floor(y * 10)),
                           static_cast<int>(std::floor(z * 10)));
  };
  for (std::size_t i = 0; i < returns.size(); ++i) {
    grid[cell(returns[i].x, returns[i].y, returns[i].z)].push_back(i);
  }
  double worst = 0.0;
  int within = 0;
  for (const auto& e : expected) {
    double best = 1e9;
    const auto [cx, cy, cz] = cell(e.x, e.y, e.z);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({cx + dx, cy + dy, cz + dz});
          if (it == grid.end()) continue;
          for (std::size_t i : it->second) {
            const auto& r = returns[i];
            best =
                std::min(best, std::hypot(double{r.x} - e.x, double{r.y} - e.y, double{r.z} - e.z));
          }
        }
    worst = std::max(worst, best);
    within += best <= 0.002;
  }
  std::printf("[ vlp32c ] %zu decoded returns, %zu expected points, %d within 2 mm, worst %.4f m\n",
              returns.size(), expected.size(), within, worst);
  // NOT yet the goal (equal count, every point within 2 mm): Storey
  // decodes with the VLP-32C manual's table, nebula with its own VLP32C.yaml
  // calibration (not in the data set); 114 more returns (0.4 %), positions up to
  // 4.7 cm apart, 7222 of 26216 within 2 mm. Guarded here at what is measured.
  EXPECT_NEAR(static_cast<double>(returns.size()), static_cast<double>(expected.size()),
              0.005 * expected.size());
  EXPECT_LT(worst, 0.05);
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
