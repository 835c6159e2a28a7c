// Writes the seed corpora of the fuzz targets (fuzz/targets/*.cpp) with the
// simulator's writers, small on purpose (a few points, packets and samples),
// plus small cuts of the real recordings when their folder is given:
//   make_seeds OUT [REAL_DATA_DIR]
// OUT/<target>/<seed> for each target; run at build time (fuzz/CMakeLists.txt).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "common/error.h"
#include "export/planes_json.h"
#include "export/point_cloud_writers.h"
#include "export/storeys_json.h"
#include "io/calibration_file.h"
#include "io/ros_message_codec.h"
#include "map/map_cloud.h"
#include "sim/bag_writer.h"
#include "sim/cloud_messages.h"
#include "sim/imu_csv_writer.h"
#include "sim/mesh.h"
#include "sim/ros2_bag_writer.h"
#include "sim/velodyne_packet_builder.h"
#include "sim/velodyne_pcap_writer.h"
#include "trajectory/tum.h"

namespace fs = std::filesystem;
using namespace storey;

namespace {

constexpr std::int64_t kStartNs = 1700000000000000000;

std::string dirOf(const fs::path& out, const std::string& target) {
  fs::create_directories(out / target);
  return (out / target).string();
}

void writeBytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

std::vector<std::uint8_t> prefixed(std::uint8_t first, const std::vector<std::uint8_t>& bytes) {
  std::vector<std::uint8_t> out{first};
  out.insert(out.end(), bytes.begin(), bytes.end());
  return out;
}

/// A scan of `n` points on 4 rings, times over 0.1 s.
Scan tinyScan(std::int64_t stamp_ns, int n) {
  Scan scan;
  scan.stamp_ns = stamp_ns;
  scan.frame_id = "velodyne";
  for (int i = 0; i < n; ++i) {
    ScanPoint p;
    const double az = 2.0 * M_PI * i / n;
    const int ring = i % 4;
    p.p =
        Eigen::Vector3f(static_cast<float>(5 * std::cos(az)), static_cast<float>(5 * std::sin(az)),
                        static_cast<float>(-0.5 + 0.3 * ring));
    p.intensity = static_cast<float>(10 * i);
    p.time = static_cast<float>(0.1 * i / n);
    p.ring = static_cast<std::uint16_t>(ring);
    scan.points.push_back(p);
  }
  return scan;
}

std::vector<ImuSample> tinyImu(int n) {
  std::vector<ImuSample> samples;
  for (int i = 0; i < n; ++i) {
    ImuSample s;
    s.stamp_ns = kStartNs + i * 2500000;
    s.gyro = Eigen::Vector3d(0.001 * i, -0.002, 0.01);
    s.accel = Eigen::Vector3d(0.1, -0.05, 9.81);
    samples.push_back(s);
  }
  return samples;
}

/// Firing sequences of `model` over `count` periods, the head turning fast so
/// the azimuth wraps (frames complete) within a few packets.
std::vector<sim::VelodyneFiring> tinyFirings(velodyne::Model model, int count) {
  std::vector<sim::VelodyneFiring> firings;
  const double period_ns = velodyne::sequencePeriod(model) * 1e9;
  for (int i = 0; i < count; ++i) {
    sim::VelodyneFiring f;
    f.t_ns = static_cast<std::int64_t>(std::llround(i * period_ns));
    f.azimuth_deg = std::fmod(i * 17.0, 360.0);
    for (int l = 0; l < velodyne::laserCount(model); ++l) {
      f.distance[l] = static_cast<std::uint16_t>(l % 5 == 0 ? 0 : 1000 + 40 * l + i);
      f.reflectivity[l] = static_cast<std::uint8_t>(l * 7 + i);
    }
    firings.push_back(f);
  }
  return firings;
}

VelodyneScanMessage tinyVelodyneScan(velodyne::Model model, int firings) {
  sim::VelodynePacketBuilder builder(kStartNs, 10.0, model, "seeds");
  VelodyneScanMessage scan;
  scan.frame_id = "velodyne";
  sim::BuiltPacket packet;
  auto keep = [&] {
    VelodynePacketMessage m;
    m.stamp_ns = packet.complete_ns;
    m.data = packet.payload;
    scan.packets.push_back(m);
    scan.stamp_ns = packet.complete_ns;
  };
  for (const auto& f : tinyFirings(model, firings))
    if (builder.add(f, packet)) keep();
  if (builder.finish(packet)) keep();
  return scan;
}

void writeSimLog(sim::SimLogWriter& log, bool packets) {
  const auto imu = tinyImu(80);
  std::size_t next_imu = 0;
  for (int k = 0; k < 2; ++k) {
    const std::int64_t stamp = kStartNs + k * 100000000;
    while (next_imu < imu.size() && imu[next_imu].stamp_ns <= stamp + 100000000) {
      const ImuSample& sample = imu[next_imu++];
      log.writeImu("/imu/data", "imu", sample, sample.stamp_ns, 1e-6, 1e-4);
    }
    if (packets) {
      VelodyneScanMessage scan = tinyVelodyneScan(velodyne::Model::kVlp16, 24 * 2);
      for (auto& p : scan.packets) p.stamp_ns += k * 100000000;
      scan.stamp_ns += k * 100000000;
      log.writeVelodyneScan("/velodyne_packets", scan, scan.stamp_ns);
    } else {
      log.writeScan("/velodyne_points", tinyScan(stamp, 24), stamp + 100000000);
    }
  }
  log.close();
}

void copyFile(const fs::path& from, const fs::path& to) {
  if (fs::exists(from)) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

/// The first `bytes` bytes of `from` (a capture cut short: the reader stops at the cut).
void copyPrefix(const fs::path& from, const fs::path& to, std::size_t bytes) {
  std::ifstream in(from, std::ios::binary);
  if (!in) return;
  std::vector<char> data(bytes);
  in.read(data.data(), static_cast<std::streamsize>(bytes));
  data.resize(static_cast<std::size_t>(in.gcount()));
  std::ofstream(to, std::ios::binary).write(data.data(), static_cast<std::streamsize>(data.size()));
}

void makeSeeds(const fs::path& out, const fs::path& real) {
  const fs::path scratch = out / "_scratch";
  fs::create_directories(scratch);

  // ROS 1 bags: point clouds (plain and LZ4 chunks) and Velodyne packets.
  const std::string rosbag = dirOf(out, "rosbag");
  {
    sim::BagWriter plain(rosbag + "/clouds.bag", sim::BagCompression::kNone);
    writeSimLog(plain, false);
    sim::BagWriter lz4(rosbag + "/clouds_lz4.bag", sim::BagCompression::kLz4);
    writeSimLog(lz4, false);
    sim::BagWriter packets(rosbag + "/packets.bag", sim::BagCompression::kNone);
    writeSimLog(packets, true);
  }

  // ROS 2 bags: sqlite3 and MCAP (each compression, chunked or not), metadata.yaml.
  const std::string db3 = dirOf(out, "db3"), mcap = dirOf(out, "mcap");
  const std::string metadata = dirOf(out, "rosbag2_metadata");
  {
    const fs::path bag = scratch / "sqlite";
    sim::Ros2BagWriter log(bag.string(), sim::Ros2Storage::kSqlite3);
    writeSimLog(log, false);
    copyFile(bag / "sqlite_0.db3", db3 + "/clouds.db3");
    copyFile(bag / "metadata.yaml", metadata + "/sqlite3.yaml");
  }
  struct McapCase {
    const char* name;
    sim::McapCompression compression;
    bool chunked, summary, packets;
  };
  for (const McapCase& c : {McapCase{"none", sim::McapCompression::kNone, true, true, false},
                            McapCase{"zstd", sim::McapCompression::kZstd, true, true, false},
                            McapCase{"lz4", sim::McapCompression::kLz4, true, false, false},
                            McapCase{"unchunked", sim::McapCompression::kNone, false, true, false},
                            McapCase{"packets", sim::McapCompression::kNone, true, true, true}}) {
    const fs::path bag = scratch / c.name;
    sim::McapWriterOptions options;
    options.compression = c.compression;
    options.chunked = c.chunked;
    options.summary = c.summary;
    sim::Ros2BagWriter log(bag.string(), sim::Ros2Storage::kMcap, options);
    writeSimLog(log, c.packets);
    copyFile(bag / (std::string(c.name) + "_0.mcap"), mcap + "/" + c.name + ".mcap");
    if (std::string(c.name) == "none") copyFile(bag / "metadata.yaml", metadata + "/mcap.yaml");
  }

  // Velodyne captures of every model, and their packets alone.
  const std::string pcap = dirOf(out, "pcap"), packet = dirOf(out, "velodyne_packet");
  for (int m = 0; m < 3; ++m) {
    const auto model = static_cast<velodyne::Model>(m);
    const std::string name = velodyne::toString(model);
    sim::VelodynePcapWriter writer(pcap + "/" + name + ".pcap", kStartNs, 10.0, model);
    for (const auto& f : tinyFirings(model, 72)) writer.add(f);
    writer.close();
    const VelodyneScanMessage scan = tinyVelodyneScan(model, 48);
    std::vector<std::uint8_t> one(scan.packets[0].data.begin(), scan.packets[0].data.end());
    writeBytes(packet + "/" + name + ".bin", prefixed(static_cast<std::uint8_t>(m), one));
    std::vector<std::uint8_t> all;
    for (const auto& p : scan.packets) all.insert(all.end(), p.data.begin(), p.data.end());
    writeBytes(packet + "/" + name + "_scan.bin", prefixed(static_cast<std::uint8_t>(m), all));
  }
  writeBytes(packet + "/position.bin", std::vector<std::uint8_t>(513, 0));

  // ROS messages, both wire formats (byte 0: format bit, then kind or model).
  const std::string pc2 = dirOf(out, "pointcloud2"), messages = dirOf(out, "ros_messages");
  for (int f = 0; f < 2; ++f) {
    const WireFormat format = f ? WireFormat::kCdr : WireFormat::kRos1;
    const auto b = static_cast<std::uint8_t>(f);
    const PointCloudMessage cloud = sim::velodyneLayoutCloud(tinyScan(kStartNs, 16));
    writeBytes(pc2 + "/velodyne_" + std::to_string(f) + ".bin",
               prefixed(b, encodePointCloud2(cloud, format)));
    ImuSample sample = tinyImu(1)[0];
    writeBytes(messages + "/imu_" + std::to_string(f) + ".bin",
               prefixed(b, encodeImu(sample, "imu", 1e-6, 1e-4, nullptr, nullptr, format)));
    writeBytes(messages + "/scan_" + std::to_string(f) + ".bin",
               prefixed(static_cast<std::uint8_t>(b | 2),
                        encodeVelodyneScan(tinyVelodyneScan(velodyne::Model::kVlp16, 48), format)));
  }

  // PCD (binary from the map writer, ascii by hand), IMU CSV, PLY, TUM, JSON, YAML.
  MapCloud map;
  for (const auto& p : tinyScan(kStartNs, 12).points) {
    map.positions.push_back(p.p);
    map.intensity.push_back(p.intensity);
    map.time.push_back(1700000000.0 + p.time);
    map.keyframe.push_back(0);
    map.storey.push_back(0);
    map.flags.push_back(0);
  }
  const std::string pcd = dirOf(out, "pcd");
  writePcd(pcd + "/binary.pcd", map);
  writeText(pcd + "/ascii.pcd",
            "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
            "FIELDS x y z intensity ring time\nSIZE 4 4 4 4 2 4\nTYPE F F F F U F\n"
            "COUNT 1 1 1 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n"
            "1 2 3 10 0 0.0\n4 5 6 20 1 0.05\n-1 -2 0.5 30 2 0.09\n");

  const std::string ply = dirOf(out, "ply");
  writePly(ply + "/points.ply", map);
  sim::TriangleMesh mesh;
  mesh.addBox({0, 0, 0}, {1, 2, 3}, sim::Surface::kWall);
  mesh.writePly(ply + "/mesh.ply");
  writeText(ply + "/ascii.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "property uchar returns\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1\n");

  const auto imu = tinyImu(6);
  const std::string csv = dirOf(out, "imu_csv");
  sim::writeImuCsv(csv + "/imu.csv", imu, 0, {"seed"});
  writeText(csv + "/ns_dps_g.csv",
            "time_ns;gyro_x_dps;gyro_y_dps;gyro_z_dps;accel_x_g;accel_y_g;accel_z_g\n"
            "1700000000000000000;0.1;0.2;0.3;0;0;1\n1700000000002500000;0.1;0.2;0.3;0;0;1.01\n");

  Trajectory trajectory;
  for (int i = 0; i < 4; ++i) {
    StampedPose p;
    p.time = 1700000000.0 + 0.1 * i;
    p.pose = Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.1 * i, 0, 0));
    trajectory.push_back(p);
  }
  writeTum(dirOf(out, "tum") + "/trajectory.tum", trajectory);

  PlaneMap planes;
  planes.keyframes = 2;
  GlobalPlane plane;
  plane.id = 3;
  plane.facing_world = Eigen::Vector3d::UnitZ();
  PlaneObservation obs;
  obs.keyframe = 1;
  obs.time = 1700000000.5;
  obs.centroid_keyframe = Eigen::Vector3d(1, 2, 0);
  obs.hull_keyframe = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  obs.points = 100;
  plane.observations.push_back(obs);
  planes.planes.push_back(plane);
  writePlanesJson(dirOf(out, "planes_json") + "/planes.json", planes);

  StoreyInfo storey;
  storey.index = 0;
  storey.ceiling_elevation = 2.6;
  storey.height = 3.0;
  storey.footprint = {{0, 0}, {10, 0}, {10, 5}};
  StoreyInfo upper = storey;
  upper.index = 1;
  upper.floor_elevation = 3.0;
  upper.height.reset();
  writeText(dirOf(out, "storeys_json") + "/storeys.json", storeysJson({storey, upper}, 0.05));

  // config_yaml: resources/config/default.yaml (every key), copied by fuzz/CMakeLists.txt.
  dirOf(out, "config_yaml");
  Calibration calibration;
  calibration.points_topic = "/velodyne_points";
  calibration.imu_topic = "/imu/data";
  writeCalibrationFile(calibration, dirOf(out, "calibration_yaml") + "/calibration.yaml");

  // Small cuts of the real recordings (../shared/data/real), when present.
  const std::string xml = dirOf(out, "veloview_xml");
  if (!real.empty() && fs::is_directory(real)) {
    copyPrefix(real / "veloview-vlp16-indoor/vlp-16-test-90deg-1-50-frames.pcap",
               pcap + "/real_vlp16.pcap", 12000);
    copyPrefix(real / "veloview-hdl32e-imu/monterey-first-100-packets.pcap",
               pcap + "/real_hdl32e_imu.pcap", 40000);
    copyPrefix(real / "nebula-vlp16-dual/vlp16-dual-4-scans.pcap", pcap + "/real_vlp16_dual.pcap",
               12000);
    copyFile(real / "veloview-vlp16-indoor/VLP-16.xml", xml + "/VLP-16.xml");
    copyFile(real / "veloview-hdl32e-imu/HDL-32.xml", xml + "/HDL-32.xml");
    copyFile(real / "nebula-vlp16-dual/rosbag2/metadata.yaml", metadata + "/real_vlp16_dual.yaml");
    copyFile(real / "nebula-vlp32c-rosbag2/rosbag2/metadata.yaml", metadata + "/real_vlp32c.yaml");
  }
  if (fs::is_empty(xml)) {
    writeText(xml + "/minimal.xml",
              "<boost_serialization><DB><distLSB_>0.2</distLSB_><points_><item><px>"
              "<vertCorrection_>-15</vertCorrection_><rotCorrection_>0</rotCorrection_>"
              "<distCorrection_>0</distCorrection_></px></item></points_></DB>"
              "</boost_serialization>\n");
  }
  fs::remove_all(scratch);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: make_seeds OUT [REAL_DATA_DIR]\n";
    return 2;
  }
  try {
    makeSeeds(argv[1], argc > 2 ? argv[2] : "");
  } catch (const std::exception& e) {
    std::cerr << "make_seeds: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
