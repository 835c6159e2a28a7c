// The simulator's Velodyne capture (simulation.pcap + imu.csv), end to end:
// the packet writer's bytes, the capture decoded by the pcap reader against
// the bag of the same simulation (points, times, rings, intensities, IMU),
// the pipeline on the capture against the ground truth, and the `storey`
// binary (simulate --pcap, info, run) on it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <variant>
#include <vector>

#include "common/error.h"
#include "config/config.h"
#include "eval/association.h"
#include "eval/ate.h"
#include "io/imu_csv.h"
#include "io/log_reader.h"
#include "io/velodyne/velodyne_packet.h"
#include "io/velodyne/velodyne_pcap_reader.h"
#include "io/velodyne/velodyne_tables.h"
#include "pipeline/pipeline.h"
#include "sim/imu_csv_writer.h"
#include "sim/lidar_model.h"
#include "sim/simulator.h"
#include "sim/velodyne_pcap_writer.h"
#include "sim/vlp16.h"
#include "support/run_storey.h"
#include "support/temp_dir.h"
#include "trajectory/tum.h"

namespace storey {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in),
                                   std::istreambuf_iterator<char>());
}
std::uint16_t be16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
}
std::uint32_t le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

// ---------------------------------------------------------------------------
// The writer alone.

TEST(SimPcapWriter, SimulatorTimingAndElevationsAreTheDecodersTables) {
  const velodyne::Calibration table = velodyne::defaultCalibration(velodyne::Model::kVlp16);
  ASSERT_EQ(static_cast<int>(table.lasers.size()), sim::vlp16::kLasers);
  for (int id = 0; id < sim::vlp16::kLasers; ++id) {
    EXPECT_DOUBLE_EQ(table.lasers[id].elevation_deg, sim::vlp16::elevationDeg(id)) << id;
    EXPECT_EQ(table.lasers[id].ring, sim::vlp16::ring(id)) << id;
  }
  EXPECT_EQ(sim::vlp16::kSequencePeriodNs, 55296);
  EXPECT_EQ(sim::vlp16::kFiringIntervalNs, 2304);
  EXPECT_DOUBLE_EQ(table.distance_resolution_m, sim::vlp16::kDistanceStep);
}

TEST(SimPcapWriter, PacketsAreTheSensorsBytes) {
  TempDir dir;
  const std::string path = dir.file("w.pcap");
  // 30 sequences: one full packet of 24 and a second one padded with no-returns.
  const std::int64_t start_ns =
      1'700'000'000'000'000'000LL + 123'456'789;  // 800.123456789 s past the hour
  const double hz = 10.0;
  const double step_deg = 360.0 * hz * 55.296e-6;
  std::vector<sim::VelodyneFiring> sequences;
  {
    sim::VelodynePcapWriter writer(path, start_ns, hz);
    for (int k = 0; k < 30; ++k) {
      sim::VelodyneFiring q;
      q.t_ns = k * 55296;
      q.azimuth_deg = std::fmod(359.5 + k * step_deg, 360.0);  // wraps inside the first packet
      for (int l = 0; l < 16; ++l) {
        q.distance[l] = static_cast<std::uint16_t>((k * 16 + l) % 5 == 0 ? 0 : 1000 + 7 * k + l);
        q.reflectivity[l] = static_cast<std::uint8_t>(k + l);
      }
      sequences.push_back(q);
      writer.add(q);
    }
    sim::VelodyneFiring late;
    late.t_ns = 31 * 55296;  // skips one
    EXPECT_THROW(writer.add(late), Error);
    writer.close();
    EXPECT_EQ(writer.packets(), 2);
    // Frames start at the first block and where the block azimuth wraps
    // (block 2: sequence 4 at 0.296 deg); none in the filled-up part.
    EXPECT_EQ(writer.frameStarts(), (std::vector<std::int64_t>{start_ns, start_ns + 4 * 55296}));
  }
  const auto bytes = readBytes(path);
  ASSERT_EQ(bytes.size(), 24u + 2u * (16u + 1248u));
  EXPECT_EQ(le32(bytes.data()), 0xA1B2C3D4u);
  EXPECT_EQ(le32(bytes.data() + 20), 1u);  // Ethernet

  const velodyne::PacketDecoder decoder(
      velodyne::defaultCalibration(velodyne::Model::kVlp16),
      velodyne::DecodeOptions{velodyne::AzimuthInterpolation::kPerLaser, 0.0, 1000.0, true, {}});
  for (int p = 0; p < 2; ++p) {
    const std::uint8_t* record = bytes.data() + 24 + p * (16 + 1248);
    const std::uint8_t* frame = record + 16;
    const std::uint8_t* payload = frame + 42;
    // Record time: the packet is complete 24 sequences after its first firing.
    const std::int64_t first_ns = start_ns + p * 24 * 55296;
    const std::int64_t record_us = (first_ns + 24 * 55296 + 500) / 1000;
    EXPECT_EQ(le32(record), static_cast<std::uint32_t>(record_us / 1'000'000));
    EXPECT_EQ(le32(record + 4), static_cast<std::uint32_t>(record_us % 1'000'000));
    EXPECT_EQ(le32(record + 8), 1248u);
    EXPECT_EQ(be16(frame + 12), 0x0800);  // IPv4
    EXPECT_EQ(frame[14 + 9], 17);         // UDP
    std::uint32_t sum = 0;                // valid IPv4 header checksum
    for (int i = 0; i < 20; i += 2) sum += be16(frame + 14 + i);
    while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
    EXPECT_EQ(sum, 0xFFFFu);
    EXPECT_EQ(be16(frame + 34), 2368);
    EXPECT_EQ(be16(frame + 36), 2368);
    EXPECT_EQ(be16(frame + 38), 8 + 1206);
    for (int b = 0; b < 12; ++b) {
      EXPECT_EQ(payload[100 * b], 0xFF);
      EXPECT_EQ(payload[100 * b + 1], 0xEE);
    }
    // Microseconds past the hour of the first firing, rounded.
    EXPECT_EQ(le32(payload + 1200),
              static_cast<std::uint32_t>(((first_ns + 500) / 1000) % 3'600'000'000LL));
    EXPECT_EQ(payload[1204], 0x37);
    EXPECT_EQ(payload[1205], 0x22);

    velodyne::DataPacket packet;
    ASSERT_EQ(decoder.decode(payload, 1206, packet), velodyne::PacketProblem::kNone);
    std::size_t r = 0;
    for (int b = 0; b < 12; ++b) {
      const int k0 = p * 24 + 2 * b;
      const double az = k0 < 30
                            ? sequences[k0].azimuth_deg
                            : std::fmod(sequences[29].azimuth_deg + (k0 - 29) * step_deg, 360.0);
      EXPECT_EQ(packet.block_azimuth[b], std::lround(az * 100.0) % 36000)
          << "packet " << p << " block " << b;
      for (int s = 0; s < 2; ++s) {
        const int k = k0 + s;
        for (int l = 0; l < 16; ++l) {
          const std::uint16_t d = k < 30 ? sequences[k].distance[l] : 0;
          if (d == 0) continue;
          ASSERT_LT(r, packet.returns.size());
          const velodyne::Return& ret = packet.returns[r++];
          EXPECT_EQ(ret.block, b);
          EXPECT_EQ(ret.sequence, s);
          EXPECT_EQ(ret.laser, l);
          EXPECT_NEAR(ret.distance, d * 0.002, 1e-6);
          EXPECT_EQ(ret.intensity, sequences[k].reflectivity[l]);
          // Decoded firing time = the sequence's time + the laser's, within the timestamp's
          // rounding.
          const double t_ns =
              static_cast<double>(le32(payload + 1200)) * 1000.0 + ret.time_offset_s * 1e9;
          const double true_ns =
              static_cast<double>((start_ns + k * 55296 + l * 2304) % 3'600'000'000'000LL);
          EXPECT_NEAR(t_ns, true_ns, 500.0);
        }
      }
    }
    EXPECT_EQ(r, packet.returns.size());
  }
}

TEST(SimPcapWriter, ImuCsvLinesReadBackExactly) {
  TempDir dir;
  std::vector<ImuSample> samples(3);
  samples[0].stamp_ns = 2'500'000;
  samples[0].gyro = Eigen::Vector3d(0.1, -1e-7, 3.141592653589793);
  samples[0].accel = Eigen::Vector3d(0.024521592031590926, -0.0, 9.81);
  samples[1].stamp_ns = 5'000'001;
  samples[1].gyro = Eigen::Vector3d(1.0 / 3.0, 2e-300, -7.0);
  samples[2].stamp_ns = 999'999'999;
  const std::int64_t start = 1'700'000'000'000'000'000LL;
  sim::writeImuCsv(dir.file("imu.csv"), samples, start, {"a comment"});
  ImuCsvReader reader(dir.file("imu.csv"), 0);
  for (const ImuSample& s : samples) {
    ImuSample read;
    ASSERT_TRUE(reader.next(read));
    EXPECT_EQ(read.stamp_ns, s.stamp_ns + start);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(read.gyro[i], s.gyro[i]);
      EXPECT_EQ(read.accel[i], s.accel[i]);
    }
  }
  ImuSample extra;
  EXPECT_FALSE(reader.next(extra));
  EXPECT_EQ(reader.badLines(), 0);
}

// ---------------------------------------------------------------------------
// `tiny` simulated once as bag + pcap.

class SimPcap : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    sim::SimulationOptions options;
    options.threads = 2;
    options.compress = false;
    options.formats.bag = true;
    options.formats.pcap = true;
    result_ = sim::simulate(sim::loadBuildingSpec("tiny"), options, dir_->file("sim"));
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static std::string simFile(const std::string& name) { return dir_->file("sim/" + name); }
  static std::string file(const std::string& name) { return dir_->file(name); }
  static Config simConfig() {
    Config c;
    applyCalibrationFile(c, simFile(sim::kCalibrationFile));
    return c;
  }

  static inline std::unique_ptr<TempDir> dir_;
  static inline sim::SimulationResult result_;
};

/// Scans of a log, read ahead as needed; IMU samples collected on the way.
class ScanSource {
 public:
  explicit ScanSource(LogReader& reader) : reader_(reader) {}
  /// Buffers at least n scans; false when the log has fewer left.
  bool fill(std::size_t n) {
    LogMessage message;
    while (scans_.size() < n && reader_.next(message)) {
      if (auto* scan = std::get_if<Scan>(&message)) {
        scans_.push_back(std::move(*scan));
      } else {
        imu.push_back(std::get<ImuSample>(message));
      }
    }
    return scans_.size() >= n;
  }
  Scan& front() { return scans_.front(); }
  Scan& at(std::size_t i) { return scans_[i]; }
  void pop() { scans_.pop_front(); }
  std::vector<ImuSample> imu;

 private:
  LogReader& reader_;
  std::deque<Scan> scans_;
};

struct CaptureComparison {
  std::int64_t bag_scans = 0, pcap_frames = 0, points = 0, pcap_points = 0;
  std::int64_t bad_points = 0, scans_with_other_count = 0, bad_frame_steps = 0;
  double max_dt_ns = 0.0, max_dp = 0.0, max_dp_per_range = 0.0, max_range = 0.0;
  double median_dp = 0.0, p99_dp = 0.0, within_2mm = 0.0, within_3mm = 0.0;
  double first_stamp_difference_ns = 0.0;
  std::int64_t imu_samples = 0, imu_differences = 0;
  std::vector<std::int64_t> frame_stamps, scan_stamps;
  std::map<std::string, std::int64_t> pcap_dropped;
  double rotation_hz = 0.0;
  std::int64_t data_packets = 0;
  std::string summary() const {
    std::ostringstream s;
    s << bag_scans << " bag scans, " << pcap_frames << " capture frames, " << points
      << " points; time error max " << max_dt_ns << " ns; position error median " << median_dp * 1e3
      << " mm, p99 " << p99_dp * 1e3 << " mm, max " << max_dp * 1e3 << " mm (at most "
      << max_dp_per_range * 1e3 << " mm per metre of range; ranges up to " << max_range
      << " m); within 2 mm " << within_2mm * 100.0 << " %, within 3 mm " << within_3mm * 100.0
      << " %";
    return s.str();
  }
};

/// Reads the bag and the capture of one simulation folder in step: the same
/// returns in the same (firing) order, compared point by point.
CaptureComparison compareCaptureWithBag(const std::string& sim_dir) {
  Config config;
  applyCalibrationFile(config, sim_dir + "/" + sim::kCalibrationFile);
  config.input.min_range = 0.0;
  config.input.max_range = 1000.0;
  const auto bag_reader = openLog(sim_dir + "/" + sim::kBagFile, config.input, config.sensor);
  VelodynePcapOptions options = velodynePcapOptions(config.input, config.sensor);
  options.min_range = 0.0;
  options.imu_csv = sim_dir + "/" + sim::kImuCsvFile;
  options.drop_scans_beyond_imu = false;
  VelodynePcapReader pcap_reader(sim_dir + "/" + sim::kPcapFile, options);
  ScanSource bag(*bag_reader), pcap(pcap_reader);

  CaptureComparison c;
  std::vector<float> dps;  // [m]
  std::int64_t within_2mm = 0, within_3mm = 0;
  std::size_t pcap_point = 0;  // next point of pcap.front()
  bool have_frame = false;
  std::int64_t frame_stamp = 0;
  const auto nextPcapPoint = [&](std::int64_t& t_ns) -> const ScanPoint* {
    while (true) {
      if (!pcap.fill(1)) return nullptr;
      Scan& frame = pcap.front();
      if (!have_frame) {
        if (c.pcap_frames == 0) {
          // the first frame starts with the simulation
        } else if (c.pcap_frames >= 2 &&
                   std::abs(frame.stamp_ns - frame_stamp - 100'000'000) > 230'000) {
          ++c.bad_frame_steps;  // frames one revolution apart (+- 2 blocks)
        }
        frame_stamp = frame.stamp_ns;
        c.frame_stamps.push_back(frame.stamp_ns);
        have_frame = true;
        ++c.pcap_frames;
      }
      if (pcap_point < frame.points.size()) {
        const ScanPoint& p = frame.points[pcap_point++];
        t_ns = frame.stamp_ns + std::llround(static_cast<double>(p.time) * 1e9);
        return &p;
      }
      pcap.pop();
      pcap_point = 0;
      have_frame = false;
    }
  };

  bool first = true;
  while (bag.fill(1)) {
    const bool has_next = bag.fill(2);
    const Scan& scan = bag.front();
    const std::int64_t end = has_next ? bag.at(1).stamp_ns - 10'000 : INT64_MAX;
    std::size_t in_window = 0;
    for (const ScanPoint& pa : scan.points) {
      std::int64_t tb = 0;
      const ScanPoint* pb = nextPcapPoint(tb);
      if (pb == nullptr) break;
      if (first) {
        c.first_stamp_difference_ns = static_cast<double>(pcap.front().stamp_ns - scan.stamp_ns);
        first = false;
      }
      const std::int64_t ta = scan.stamp_ns + std::llround(static_cast<double>(pa.time) * 1e9);
      in_window += tb >= scan.stamp_ns - 10'000 && tb < end;
      const double dt = std::abs(static_cast<double>(ta - tb));
      const double range = pa.p.cast<double>().norm();
      const double dp = (pa.p - pb->p).cast<double>().norm();
      c.max_dt_ns = std::max(c.max_dt_ns, dt);
      c.max_dp = std::max(c.max_dp, dp);
      c.max_dp_per_range = std::max(c.max_dp_per_range, dp / range);
      c.max_range = std::max(c.max_range, range);
      dps.push_back(static_cast<float>(dp));
      within_2mm += dp <= 0.002;
      within_3mm += dp <= 0.003;
      // Distances are the same 2 mm steps; the azimuth is sent in 0.01 deg and
      // interpolated per laser from the next block's: up to ~0.013 deg off.
      const bool ok = dt <= 1000.0 && pa.ring == pb->ring && pa.intensity == pb->intensity &&
                      std::abs(range - pb->p.cast<double>().norm()) < 1e-4 &&
                      dp <= 1e-3 + range * 2.5e-4;
      if (!ok && ++c.bad_points <= 5) {
        ADD_FAILURE() << "point " << c.points << ": dt " << dt << " ns, dp " << dp * 1e3
                      << " mm at range " << range << " m, ring " << pa.ring << "/" << pb->ring
                      << ", intensity " << pa.intensity << "/" << pb->intensity;
      }
      ++c.points;
    }
    if (in_window != scan.points.size() && ++c.scans_with_other_count <= 5) {
      ADD_FAILURE() << "bag scan " << c.bag_scans << ": " << scan.points.size()
                    << " points, the capture has " << in_window << " in its time span";
    }
    ++c.bag_scans;
    c.scan_stamps.push_back(scan.stamp_ns);
    bag.pop();
  }
  std::int64_t t = 0;
  while (nextPcapPoint(t) != nullptr) ++c.pcap_points;  // left over (should be none)
  c.pcap_points += c.points;

  if (!dps.empty()) {
    std::sort(dps.begin(), dps.end());
    c.median_dp = dps[dps.size() / 2];
    c.p99_dp = dps[static_cast<std::size_t>(0.99 * static_cast<double>(dps.size() - 1))];
    c.within_2mm = static_cast<double>(within_2mm) / static_cast<double>(dps.size());
    c.within_3mm = static_cast<double>(within_3mm) / static_cast<double>(dps.size());
  }
  // The IMU CSV is the bag's IMU, sample for sample.
  c.imu_samples = static_cast<std::int64_t>(bag.imu.size());
  if (pcap.imu.size() != bag.imu.size()) c.imu_differences = -1;
  for (std::size_t i = 0; c.imu_differences >= 0 && i < bag.imu.size(); ++i) {
    c.imu_differences += pcap.imu[i].stamp_ns != bag.imu[i].stamp_ns ||
                         pcap.imu[i].gyro != bag.imu[i].gyro ||
                         pcap.imu[i].accel != bag.imu[i].accel;
  }
  c.pcap_dropped = pcap_reader.stats().dropped;
  c.rotation_hz = pcap_reader.rotationHz();
  c.data_packets = pcap_reader.dataPackets();
  // The calibration's model, told from the product id (HDL-32E's 0x21, also
  // sent by early VLP-16 firmware, by the packets' period).
  const velodyne::Model model = *sim::velodyneModel(config.sensor.lidar_model);
  EXPECT_EQ(pcap_reader.probe().model, model);
  if (model != velodyne::Model::kHdl32e) {
    EXPECT_TRUE(pcap_reader.probe().model_from_product_id);
  }
  return c;
}

void expectCaptureIsTheBag(const CaptureComparison& c) {
  std::cout << "[ info ] " << c.summary() << "\n";
  EXPECT_EQ(c.bad_points, 0);
  EXPECT_EQ(c.scans_with_other_count, 0);
  EXPECT_EQ(c.bad_frame_steps, 0);
  EXPECT_EQ(c.pcap_points, c.points) << "the capture has the bag's points, no more";
  EXPECT_LE(c.max_dt_ns, 1000.0) << "per-point times within 1 us";
  EXPECT_NEAR(c.first_stamp_difference_ns, 0.0, 1000.0);
  // Frames are cut at the calibration's lidar.cut_angle_deg, 180 deg, where
  // the simulator's scans start (behind the robot): one frame per scan, each
  // starting at a block within one firing sequence of its scan's stamp.
  EXPECT_EQ(c.pcap_frames, c.bag_scans);
  EXPECT_EQ(static_cast<std::int64_t>(c.frame_stamps.size()), c.pcap_frames);
  std::int64_t worst_start_ns = 0;
  for (std::size_t i = 0; i < std::min(c.frame_stamps.size(), c.scan_stamps.size()); ++i)
    worst_start_ns = std::max(worst_start_ns, std::abs(c.frame_stamps[i] - c.scan_stamps[i]));
  EXPECT_LE(worst_start_ns, 55'296 + 1'000);
  EXPECT_NEAR(c.rotation_hz, 10.0, 0.01);
  EXPECT_EQ(c.imu_differences, 0) << "IMU CSV = the bag's IMU (" << c.imu_samples << " samples)";
  for (const auto& [reason, count] : c.pcap_dropped) {
    if (count != 0) {
      EXPECT_EQ(reason, kDropPointsNoReturn) << count;  // dropouts, misses, glass
    }
  }
}

TEST_F(SimPcap, OutputFolderHoldsBothLogs) {
  for (const char* name :
       {sim::kBagFile, sim::kPcapFile, sim::kImuCsvFile, sim::kPcapLidarTruthFile}) {
    EXPECT_TRUE(fs::exists(simFile(name))) << name;
  }
  // The sequences of the complete revolutions, in packets of 24 (the last one
  // filled up with no-returns): 753.5 packets/s of 1264 bytes (record header + frame).
  const std::int64_t sequences = (result_.scans * 100'000'000LL + 55295) / 55296;
  EXPECT_EQ(result_.pcap_packets, (sequences + 23) / 24);
  const auto size = fs::file_size(simFile(sim::kPcapFile));
  EXPECT_EQ(size, 24u + 1264u * static_cast<std::uintmax_t>(result_.pcap_packets));
  std::cout << "[ info ] tiny: " << result_.pcap_packets << " packets, " << size / 1e6
            << " MB pcap, " << fs::file_size(simFile(sim::kBagFile)) / 1e6
            << " MB bag (uncompressed), " << fs::file_size(simFile(sim::kImuCsvFile)) / 1e6
            << " MB imu.csv\n";
}

/// The capture's ground truth is stamped at its frames' stamps (within the
/// packet timestamp's microsecond).
void expectTruthAtFrameStamps(const CaptureComparison& c, const std::string& truth_path) {
  const Trajectory truth = readTum(truth_path);
  ASSERT_EQ(truth.size(), c.frame_stamps.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    worst =
        std::max(worst, std::abs(truth[i].time - static_cast<double>(c.frame_stamps[i]) * 1e-9));
  }
  EXPECT_LT(worst, 1.0e-6) << "[s]";
}

TEST_F(SimPcap, DecodedCaptureIsTheBagsScans) {
  const CaptureComparison c = compareCaptureWithBag(dir_->file("sim"));
  expectCaptureIsTheBag(c);
  expectTruthAtFrameStamps(c, simFile(sim::kPcapLidarTruthFile));
  EXPECT_EQ(c.bag_scans, result_.scans);
  EXPECT_EQ(c.points, result_.points);
  EXPECT_EQ(c.data_packets, result_.pcap_packets);
  RecordProperty("position_error_max_mm", std::to_string(c.max_dp * 1e3));
  RecordProperty("time_error_max_ns", std::to_string(c.max_dt_ns));
}

/// The same comparison on any simulation folder written with bag and pcap
/// (`storey simulate default -o DIR --pcap`): STOREY_SIM_PCAP_DIR=DIR.
TEST(SimPcapFolder, DecodedCaptureIsTheBagsScans) {
  const char* dir = std::getenv("STOREY_SIM_PCAP_DIR");
  if (dir == nullptr || *dir == '\0') GTEST_SKIP() << "STOREY_SIM_PCAP_DIR not set";
  const CaptureComparison c = compareCaptureWithBag(dir);
  expectCaptureIsTheBag(c);
  expectTruthAtFrameStamps(c, std::string(dir) + "/" + sim::kPcapLidarTruthFile);
}

/// The VLP-32C's and the HDL-32E's captures (32-laser blocks, their product
/// ids, timing and distance steps) decode to their bags' scans too.
TEST(SimPcapModels, Vlp32cAndHdl32eCapturesAreTheirBags) {
  for (const LidarModel model : {LidarModel::kVlp32c, LidarModel::kHdl32e}) {
    SCOPED_TRACE(toString(model));
    TempDir dir;
    sim::BuildingSpec spec = sim::loadBuildingSpec("tiny");
    spec.sensors.lidar.model = model;
    sim::SimulationOptions options;
    options.max_duration = 4.0;
    options.formats.pcap = true;
    const sim::SimulationResult result = sim::simulate(spec, options, dir.file("sim"));
    const CaptureComparison c = compareCaptureWithBag(dir.file("sim"));
    EXPECT_EQ(c.data_packets, result.pcap_packets);
    // 12 firing sequences per packet: 663.552 us (VLP-32C) or 552.96 us (HDL-32E).
    const double packet_s = model == LidarModel::kVlp32c ? 663.552e-6 : 552.96e-6;
    EXPECT_NEAR(result.pcap_packets * packet_s, result.scans * 0.1, 2 * packet_s);
    expectCaptureIsTheBag(c);
    EXPECT_EQ(c.points, result.points);
    expectTruthAtFrameStamps(c, dir.file("sim/" + std::string(sim::kPcapLidarTruthFile)));
  }
}

TEST_F(SimPcap, CaptureClockGivesTheSensorTimes) {
  // Record times are when each packet is complete, on the sensor's clock.
  VelodynePcapOptions options;
  options.imu_csv = simFile(sim::kImuCsvFile);
  options.drop_scans_beyond_imu = false;
  VelodynePcapReader sensor_clock(simFile(sim::kPcapFile), options);
  options.capture_clock = true;
  VelodynePcapReader capture_clock(simFile(sim::kPcapFile), options);
  ScanSource a(sensor_clock), b(capture_clock);
  std::size_t frames = 0;
  double worst_ns = 0.0;
  while (a.fill(1)) {
    ASSERT_TRUE(b.fill(1)) << "frame " << frames;
    EXPECT_EQ(a.front().points.size(), b.front().points.size()) << "frame " << frames;
    worst_ns =
        std::max(worst_ns, std::abs(static_cast<double>(a.front().stamp_ns - b.front().stamp_ns)));
    a.pop();
    b.pop();
    ++frames;
  }
  EXPECT_FALSE(b.fill(1));
  // The default cut (0 deg, where the azimuth wraps; the simulator's scans
  // start at 180 deg): a half revolution at each end, one frame more than scans.
  EXPECT_EQ(frames, static_cast<std::size_t>(result_.scans + 1));
  EXPECT_LE(worst_ns, 1000.0);
}

double ateSe3(const Trajectory& gt, const Trajectory& est) {
  return eval::absoluteTrajectoryError(eval::associate(gt, est), eval::Alignment::kSe3)
      .translation.rmse;
}

TEST_F(SimPcap, PipelineOnTheCaptureFollowsTheTruth) {
  Config config = simConfig();
  config.input.imu_csv = simFile(sim::kImuCsvFile);
  const PipelineResult on_pcap = runPipeline(simFile(sim::kPcapFile), config, file("run_pcap"));
  const PipelineResult on_bag = runPipeline(simFile(sim::kBagFile), simConfig(), file("run_bag"));
  const Trajectory gt = readTum(simFile(sim::kLidarTruthFile));
  const Trajectory gt_pcap = readTum(simFile(sim::kPcapLidarTruthFile));
  EXPECT_GE(on_pcap.trajectory.size() + 3, gt_pcap.size());
  const double ate_pcap = ateSe3(gt_pcap, on_pcap.trajectory);
  const double ate_bag = ateSe3(gt, on_bag.trajectory);
  std::cout << "[ info ] ATE RMSE after SE(3) alignment: pcap " << ate_pcap << " m ("
            << on_pcap.trajectory.size() << " poses), bag " << ate_bag << " m ("
            << on_bag.trajectory.size() << " poses)\n";
  EXPECT_LT(ate_pcap, 0.05);
  EXPECT_LT(ate_pcap, std::max(0.02, 2.0 * ate_bag)) << "comparable to the bag's run";
  const double unaligned = eval::absoluteTrajectoryError(
                               eval::associate(gt_pcap, on_pcap.trajectory), eval::Alignment::kNone)
                               .translation.rmse;
  EXPECT_LT(unaligned, 0.10) << "same world frame as the truth without alignment";
  RecordProperty("ate_se3_pcap_m", std::to_string(ate_pcap));
  RecordProperty("ate_se3_bag_m", std::to_string(ate_bag));
}

TEST_F(SimPcap, StoreyBinaryInfoAndRunOnTheCapture) {
  const std::string q_pcap = test::shellQuoted(simFile(sim::kPcapFile));
  const std::string q_csv = test::shellQuoted(simFile(sim::kImuCsvFile));
  const test::RunResult info =
      test::runStorey("info " + q_pcap + " --imu-csv " + q_csv, dir_->path().string());
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("VLP-16"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("10.00 Hz"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("strongest return"), std::string::npos) << info.out;

  const std::string out = file("cli_run");
  const test::RunResult run =
      test::runStorey("run " + q_pcap + " --imu-csv " + q_csv + " --calibration " +
                          test::shellQuoted(simFile(sim::kCalibrationFile)) + " -o " +
                          test::shellQuoted(out) + " --no-render",
                      dir_->path().string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_TRUE(fs::exists(out + "/trajectory.tum")) << run.err;
  const Trajectory est = readTum(out + "/trajectory.tum");
  EXPECT_GE(est.size() + 3, static_cast<std::size_t>(result_.scans));
  EXPECT_LT(ateSe3(readTum(simFile(sim::kPcapLidarTruthFile)), est), 0.05);
}

TEST(SimPcapCli, SimulateWritesTheCaptureWithoutTheBag) {
  TempDir dir;
  const std::string out = dir.file("sim");
  const test::RunResult r =
      test::runStorey("simulate tiny -o " + test::shellQuoted(out) +
                          " --pcap --no-bag --duration 3 --no-progress --threads 2",
                      dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("data packets"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out + "/" + sim::kPcapFile));
  EXPECT_TRUE(fs::exists(out + "/" + sim::kImuCsvFile));
  EXPECT_TRUE(fs::exists(out + "/" + sim::kLidarTruthFile));
  EXPECT_TRUE(fs::exists(out + "/" + sim::kPcapLidarTruthFile));
  EXPECT_FALSE(fs::exists(out + "/" + sim::kBagFile));
  // About 3 s of packets (754 per second).
  const auto packets = (fs::file_size(out + "/" + sim::kPcapFile) - 24) / 1264;
  EXPECT_NEAR(static_cast<double>(packets), 3.0 / 1327.104e-6, 80.0);

  const test::RunResult none = test::runStorey(
      "simulate tiny -o " + test::shellQuoted(dir.file("none")) + " --no-bag --no-progress",
      dir.path().string());
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.err.find("--no-bag"), std::string::npos) << none.err;
}

}  // namespace
}  // namespace storey
