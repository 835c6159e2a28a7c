#include "io/velodyne/velodyne_pcap_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <sstream>

#include "common/error.h"
#include "common/log.h"
#include "io/imu_csv.h"
#include "io/message_sequencer.h"
#include "io/velodyne/frame_assembler.h"
#include "io/velodyne/packet_model.h"
#include "io/velodyne/pcap_file.h"

namespace storey {
namespace {

using velodyne::Model;

constexpr int kProbeDataPackets = 400;
constexpr int kProbeRecords = 5000;
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
constexpr double kStandardGravity = 9.80665;
/// IMU CSV samples are pushed this far ahead of the LiDAR stream [ns].
constexpr std::int64_t kCsvLeadNs = 200'000'000;
/// IMU CSV samples earlier than the first scan by more than this are skipped [ns].
constexpr std::int64_t kCsvBeforeLogNs = 2'000'000'000;

bool isPositionWithImu(const std::uint8_t* data, std::size_t size) {
  if (size < 38) return false;
  for (std::size_t i = 14; i < 38; ++i) {
    if (data[i] != 0) return true;
  }
  return false;
}

struct HeldPacket {
  std::int64_t t_ns;
  std::uint64_t arrival;
  std::vector<std::uint8_t> bytes;
};
struct LaterPacket {
  bool operator()(const HeldPacket& a, const HeldPacket& b) const {
    return a.t_ns != b.t_ns ? a.t_ns > b.t_ns : a.arrival > b.arrival;
  }
};

}  // namespace

VelodynePcapOptions velodynePcapOptions(const InputConfig& input, const SensorConfig& sensor) {
  VelodynePcapOptions o;
  const InputConfig& in = input;
  if (in.velodyne_model == "VLP-16") o.model = Model::kVlp16;
  if (in.velodyne_model == "VLP-32C") o.model = Model::kVlp32c;
  if (in.velodyne_model == "HDL-32E") o.model = Model::kHdl32e;
  o.calibration_xml = in.velodyne_calibration;
  o.min_range = in.min_range;
  o.max_range = in.max_range;
  o.cut_angle_deg = in.velodyne_cut_angle_deg;
  o.capture_clock = in.pcap_clock == "capture";
  o.data_port = static_cast<std::uint16_t>(in.pcap_data_port);
  o.position_port = static_cast<std::uint16_t>(in.pcap_position_port);
  o.imu_csv = in.imu_csv;
  o.imu_csv_offset_ns = secondsToNs(in.imu_csv_time_offset);
  o.lidar_to_imu_offset_ns = secondsToNs(sensor.time_offset_lidar_to_imu);
  return o;
}

struct VelodynePcapReader::Impl {
  Impl(const std::string& path, const VelodynePcapOptions& options)
      : path_(path),
        options_(options),
        pcap_(path),
        sequencer_(sequencerOptions(options), stats_) {}

  static MessageSequencer::Options sequencerOptions(const VelodynePcapOptions& o) {
    MessageSequencer::Options s;
    s.lidar_to_imu_offset_ns = o.lidar_to_imu_offset_ns;
    return s;
  }

  bool isDataPort(const velodyne::UdpDatagram& d) const {
    if (options_.data_port == 0) {
      return d.size >= 4 && d.payload[0] == 0xFF && d.payload[1] == 0xEE;
    }
    return d.dst_port == options_.data_port || d.src_port == options_.data_port;
  }
  bool isPositionPort(const velodyne::UdpDatagram& d) const {
    if (options_.position_port == 0)
      return d.size <= velodyne::kPositionPacketSize && d.size > 0 && !isDataPort(d);
    return d.dst_port == options_.position_port || d.src_port == options_.position_port;
  }

  void probe() {
    velodyne::PcapFile file(path_);
    velodyne::UdpDatagram d;
    std::vector<std::int64_t> stamps;
    std::map<std::uint16_t, std::int64_t> ports;
    bool first = true;
    while (probe_.data_packets < kProbeDataPackets && file.records() < kProbeRecords &&
           file.next(d)) {
      ++ports[d.dst_port];
      if (isDataPort(d) && d.size == velodyne::kDataPacketSize && d.payload[0] == 0xFF &&
          d.payload[1] == 0xEE) {
        std::uint32_t toh;
        std::uint8_t mode, product;
        velodyne::peekDataPacket(d.payload, d.size, toh, mode, product);
        if (first) {
          probe_.product = product;
          probe_.return_mode = mode;
          first = false;
        }
        stamps.push_back(options_.capture_clock ? d.record_ns : std::int64_t{toh} * 1000);
        ++probe_.data_packets;
      } else if (isPositionPort(d) && d.size == velodyne::kPositionPacketSize &&
                 isPositionWithImu(d.payload, d.size)) {
        ++probe_.position_packets;
      }
    }
    if (probe_.data_packets == 0) {
      std::string seen;
      for (const auto& [port, count] : ports) {
        seen +=
            (seen.empty() ? "" : ", ") + std::to_string(count) + " on port " + std::to_string(port);
      }
      std::string where = file.cutAt().empty() ? "" : "; the file is cut: " + file.cutAt();
      throw Error(
          path_ + ": no Velodyne data packet (1206-byte UDP payload starting 0xFF 0xEE on port " +
          std::to_string(options_.data_port) + ") in the first " + std::to_string(file.records()) +
          " records (UDP datagrams: " + (seen.empty() ? "none" : seen) + ")" + where);
    }
    std::vector<double> steps;
    for (std::size_t i = 1; i < stamps.size(); ++i) {
      const std::int64_t step = stamps[i] - stamps[i - 1];
      if (step > 0 && step < 100'000'000) steps.push_back(static_cast<double>(step) * 1e-9);
    }
    if (!steps.empty()) {
      std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
      probe_.packet_period_s = steps[steps.size() / 2];
    }
    const velodyne::ModelDetection detected =
        velodyne::detectModel(probe_.product, probe_.return_mode, probe_.packet_period_s,
                              options_.model ? &*options_.model : nullptr, path_);
    probe_.model = detected.model;
    probe_.model_from_product_id = detected.from_product_id;
  }

  void open() {
    probe();
    velodyne::DecodeOptions decode;
    decode.azimuth = options_.azimuth;
    decode.min_range = options_.min_range;
    decode.max_range = options_.max_range;
    decoder_ = std::make_unique<velodyne::PacketDecoder>(
        velodyne::calibrationFor(probe_.model, options_.calibration_xml), decode);
    frames_ = std::make_unique<velodyne::FrameAssembler>(
        *decoder_, velodyne::kMaxFrameGapS, velodyne::cutAzimuth(options_.cut_angle_deg));
    if (!options_.imu_csv.empty()) {
      csv_ = std::make_unique<ImuCsvReader>(options_.imu_csv, options_.imu_csv_offset_ns);
      if (probe_.position_packets > 0) {
        logInfo(path_ + ": IMU from " + options_.imu_csv +
                "; the HDL-32E position packets are ignored");
      }
    } else if (probe_.position_packets > 0) {
      imu_from_packets_ = true;
    } else if (options_.require_imu) {
      throw Error(path_ +
                  ": no IMU: the capture holds no HDL-32E position packet with IMU values; "
                  "give an IMU CSV (input.imu_csv, --imu-csv)");
    }
  }

  /// Absolute time of a packet timestamp (microseconds past the hour) on the sensor clock.
  std::int64_t sensorTime(std::uint32_t toh_us, std::int64_t record_ns, bool advance) {
    return clock_.place(toh_us, record_ns, advance);
  }

  void countPacketProblem(velodyne::PacketProblem problem) {
    ++stats_.dropped[velodyne::toString(problem)];
  }

  /// Reads one datagram; false at the end of the capture.
  bool readOne() {
    velodyne::UdpDatagram d;
    if (!pcap_.next(d)) return false;
    ++ports_[d.dst_port];
    if (isDataPort(d) && (options_.data_port != 0 || d.size >= 2)) {
      if (d.size != velodyne::kDataPacketSize) {
        ++stats_.dropped[d.size < velodyne::kDataPacketSize ? kDropPacketTruncated
                                                            : "velodyne_packet_wrong_size"];
        return true;
      }
      std::uint32_t toh;
      std::uint8_t mode, product;
      velodyne::peekDataPacket(d.payload, d.size, toh, mode, product);
      std::int64_t t = 0;
      if (options_.capture_clock) {
        t = d.record_ns - static_cast<std::int64_t>(
                              velodyne::packetPeriod(decoder_->model(), mode == 0x39) * 1e9);
      } else {
        t = sensorTime(toh, d.record_ns, true);
      }
      hold(t, d);
      return true;
    }
    if (isPositionPort(d)) {
      readPosition(d);
      return true;
    }
    ++stats_.dropped[kDropNotVelodyne];
    return true;
  }

  void readPosition(const velodyne::UdpDatagram& d) {
    if (d.size != velodyne::kPositionPacketSize) {
      ++stats_.dropped[kDropPositionTruncated];
      return;
    }
    if (!imu_from_packets_) return;
    if (!isPositionWithImu(d.payload, d.size)) {
      ++stats_.dropped[kDropPositionNoImu];
      return;
    }
    velodyne::PositionPacket packet;
    velodyne::decodePositionPacket(d.payload, d.size, packet);
    ImuSample imu;
    imu.stamp_ns =
        options_.capture_clock ? d.record_ns : sensorTime(packet.timestamp_us, d.record_ns, false);
    // Axes (docs/formats.md): z up = the two vertical accelerometer axes
    // (boards 1 and 2, X), x and y = board 3's horizontal axes; gyros 1, 2, 3
    // about x, y, z.
    imu.gyro =
        Eigen::Vector3d(packet.gyro_dps[0], packet.gyro_dps[1], packet.gyro_dps[2]) * kDegToRad;
    imu.accel = Eigen::Vector3d(packet.accel_g[4], packet.accel_g[5],
                                0.5 * (packet.accel_g[0] + packet.accel_g[2])) *
                kStandardGravity;
    noteImu(imu.stamp_ns);
    sequencer_.push(imu);
  }

  bool imuSourceExists() const { return csv_ != nullptr || imu_from_packets_; }
  void noteImu(std::int64_t stamp_ns) {
    last_imu_ns_ = have_imu_ ? std::max(last_imu_ns_, stamp_ns) : stamp_ns;
    have_imu_ = true;
    releaseCoveredScans();
  }

  /// Puts a data packet into the reorder buffer and releases the oldest when full.
  void hold(std::int64_t t_ns, const velodyne::UdpDatagram& d) {
    if (have_released_ && t_ns <= released_ns_) {
      ++stats_.dropped[t_ns == released_ns_ ? kDropPacketDuplicate : kDropPacketLate];
      return;
    }
    if (have_arrived_ && t_ns < newest_arrived_ns_) ++stats_.dropped[kReorderedPackets];
    newest_arrived_ns_ = have_arrived_ ? std::max(newest_arrived_ns_, t_ns) : t_ns;
    have_arrived_ = true;
    held_.push_back(
        HeldPacket{t_ns, arrivals_++, std::vector<std::uint8_t>(d.payload, d.payload + d.size)});
    std::push_heap(held_.begin(), held_.end(), LaterPacket());
    if (held_.size() > options_.reorder_packets) releaseOne();
  }

  void releaseOne() {
    std::pop_heap(held_.begin(), held_.end(), LaterPacket());
    HeldPacket packet = std::move(held_.back());
    held_.pop_back();
    if (have_released_ && packet.t_ns == released_ns_) {
      ++stats_.dropped[kDropPacketDuplicate];
      return;
    }
    have_released_ = true;
    released_ns_ = packet.t_ns;
    const auto problem = decoder_->decode(packet.bytes.data(), packet.bytes.size(), decoded_);
    if (problem != velodyne::PacketProblem::kNone) {
      countPacketProblem(problem);
      return;
    }
    if (decoded_.product != probe_.product && decoded_.product != 0 && probe_.product != 0 &&
        decoded_.product != velodyne::kProductHdl32e &&
        decoded_.product != velodyne::kProductVlp16) {
      ++stats_.dropped[kDropPacketOtherModel];
      return;
    }
    ++data_packets_;
    stats_.dropped[kDropPointsNoReturn] += decoded_.counts.no_return;
    stats_.dropped[kDropPointsRange] += decoded_.counts.out_of_range;
    if (decoded_.counts.identical_second > 0) {
      stats_.dropped[kDropPointsDualIdentical] += decoded_.counts.identical_second;
    }
    updateRotation(packet.t_ns);
    std::vector<Scan> done;
    frames_->add(decoded_, packet.t_ns, done);
    for (auto& scan : done) pushScan(std::move(scan));
  }

  void updateRotation(std::int64_t t_ns) {
    const int first = decoded_.block_azimuth[0];
    if (have_rotation_sample_) {
      const double dt = static_cast<double>(t_ns - last_rotation_ns_) * 1e-9;
      const int dazimuth = (first - last_rotation_azimuth_ + 36000) % 36000;
      if (dt > 0.0 && dt < 0.05) {
        rotation_steps_.push_back({dt, dazimuth / 36000.0});
        rotation_time_s_ += dt;
        rotation_turns_ += dazimuth / 36000.0;
        if (rotation_steps_.size() > 2000) {
          rotation_time_s_ -= rotation_steps_.front().first;
          rotation_turns_ -= rotation_steps_.front().second;
          rotation_steps_.pop_front();
        }
      }
    }
    have_rotation_sample_ = true;
    last_rotation_ns_ = t_ns;
    last_rotation_azimuth_ = first;
  }

  void pushScan(Scan&& scan) {
    if (csv_) feedCsv(scan.stamp_ns + options_.lidar_to_imu_offset_ns + kCsvLeadNs, scan.stamp_ns);
    last_scan_ns_ = scan.stamp_ns;
    if (!imuSourceExists() || !options_.drop_scans_beyond_imu) {
      sequencer_.push(std::move(scan));
      return;
    }
    awaiting_imu_.push_back(std::move(scan));
    releaseCoveredScans();
  }

  /// Scans wait until an IMU sample at or after their last point has been read.
  void releaseCoveredScans() {
    while (!awaiting_imu_.empty() && have_imu_) {
      const Scan& scan = awaiting_imu_.front();
      const std::int64_t end_ns =
          scan.stamp_ns + secondsToNs(scan.timeSpan().second) + options_.lidar_to_imu_offset_ns;
      if (end_ns > last_imu_ns_) break;
      sequencer_.push(std::move(awaiting_imu_.front()));
      awaiting_imu_.pop_front();
    }
  }

  /// Pushes the CSV's samples up to `until_ns`.
  void feedCsv(std::int64_t until_ns, std::int64_t scan_ns) {
    if (!have_csv_sample_ && !csv_done_) {
      have_csv_sample_ = csv_->next(csv_sample_);
      csv_done_ = !have_csv_sample_;
    }
    while (have_csv_sample_ && csv_sample_.stamp_ns <= until_ns) {
      if (csv_sample_.stamp_ns < scan_ns - kCsvBeforeLogNs && csv_pushed_ == 0) {
        ++stats_.dropped[kDropImuBeforeLog];
      } else {
        noteImu(csv_sample_.stamp_ns);
        sequencer_.push(csv_sample_);
        ++csv_pushed_;
      }
      have_csv_sample_ = csv_->next(csv_sample_);
      csv_done_ = !have_csv_sample_;
    }
  }

  void finishInput() {
    while (!held_.empty()) releaseOne();
    std::vector<Scan> done;
    frames_->flush(done);
    if (csv_ && !done.empty()) {  // the CSV samples up to the last scan's end
      feedCsv(done.back().stamp_ns + options_.lidar_to_imu_offset_ns + kCsvLeadNs + 1'000'000'000,
              done.back().stamp_ns);
    }
    for (auto& scan : done) pushScan(std::move(scan));
    // The last revolutions may outlast the IMU stream by a few packets: a scan
    // the IMU does not cover cannot be deskewed.
    releaseCoveredScans();
    stats_.dropped[kDropScanBeyondImu] += static_cast<std::int64_t>(awaiting_imu_.size());
    if (stats_.dropped[kDropScanBeyondImu] == 0) stats_.dropped.erase(kDropScanBeyondImu);
    awaiting_imu_.clear();
    if (csv_) {
      if (stats_.scans + static_cast<std::int64_t>(sequencer_.buffered()) > 0) {
        feedCsv(last_scan_ns_ + options_.lidar_to_imu_offset_ns + kCsvLeadNs + 1'000'000'000,
                last_scan_ns_);
      }
      if (csv_->badLines() > 0) stats_.dropped[kDropImuCsvBadLine] = csv_->badLines();
      if (csv_pushed_ == 0) {
        logWarning(options_.imu_csv +
                   ": no IMU sample overlaps the capture's time span (check "
                   "the CSV's time base and input.imu_csv_time_offset)");
      }
    }
    for (const auto& [reason, count] : pcap_.skipped()) stats_.dropped[reason] += count;
    if (!pcap_.cutAt().empty()) {
      logWarning(path_ + ": reading stopped at a damaged or cut record: " + pcap_.cutAt());
    }
    std::int64_t skipped_packets = 0;
    std::string reasons;
    for (const auto& [reason, count] : stats_.dropped) {
      if (count == 0 || reason.find("_point_") != std::string::npos ||
          reason == kReorderedPackets) {
        continue;
      }
      skipped_packets += count;
      reasons += (reasons.empty() ? "" : ", ") + reason + " " + std::to_string(count);
    }
    if (skipped_packets > 0) logWarning(path_ + ": skipped " + reasons);
    const auto reordered = stats_.dropped.find(kReorderedPackets);
    if (reordered != stats_.dropped.end() && reordered->second > 0) {
      logWarning(path_ + ": " + std::to_string(reordered->second) +
                 " data packets arrived out of order and were put back in order");
    }
    sequencer_.finish();
  }

  bool next(LogMessage& message) {
    while (!sequencer_.pop(message)) {
      if (ended_) return false;
      if (!readOne()) {
        ended_ = true;
        finishInput();
      }
    }
    return true;
  }

  /// Turns over time of the last packets (up to 2000).
  double rotationHz() const {
    return rotation_time_s_ > 0.0 ? rotation_turns_ / rotation_time_s_ : 0.0;
  }

  std::string path_;
  VelodynePcapOptions options_;
  velodyne::PcapFile pcap_;
  VelodyneProbe probe_;
  std::unique_ptr<velodyne::PacketDecoder> decoder_;
  std::unique_ptr<velodyne::FrameAssembler> frames_;
  std::unique_ptr<ImuCsvReader> csv_;
  bool imu_from_packets_ = false;
  LogReadStats stats_;
  MessageSequencer sequencer_;
  velodyne::DataPacket decoded_;
  std::map<std::uint16_t, std::int64_t> ports_;
  bool ended_ = false;
  velodyne::HourClock clock_;  ///< sensor clock
  // Reordering.
  std::vector<HeldPacket> held_;
  std::uint64_t arrivals_ = 0;
  bool have_released_ = false;
  std::int64_t released_ns_ = 0;
  bool have_arrived_ = false;
  std::int64_t newest_arrived_ns_ = 0;
  std::int64_t data_packets_ = 0;
  // Rotation rate.
  std::deque<std::pair<double, double>> rotation_steps_;  ///< (seconds, turns) per packet step
  double rotation_time_s_ = 0.0;
  double rotation_turns_ = 0.0;
  bool have_rotation_sample_ = false;
  std::int64_t last_rotation_ns_ = 0;
  int last_rotation_azimuth_ = 0;
  // IMU CSV.
  ImuSample csv_sample_;
  bool have_csv_sample_ = false;
  bool csv_done_ = false;
  std::int64_t csv_pushed_ = 0;
  std::int64_t last_scan_ns_ = 0;
  bool have_imu_ = false;
  std::int64_t last_imu_ns_ = 0;   ///< newest IMU stamp pushed
  std::deque<Scan> awaiting_imu_;  ///< scans not yet covered by the IMU
};

VelodynePcapReader::VelodynePcapReader(const std::string& path, const VelodynePcapOptions& options)
    : impl_(std::make_unique<Impl>(path, options)) {
  impl_->open();
}

VelodynePcapReader::~VelodynePcapReader() = default;

bool VelodynePcapReader::next(LogMessage& message) {
  return impl_->next(message);
}
const LogReadStats& VelodynePcapReader::stats() const {
  return impl_->stats_;
}
const VelodyneProbe& VelodynePcapReader::probe() const {
  return impl_->probe_;
}
double VelodynePcapReader::rotationHz() const {
  return impl_->rotationHz();
}
std::int64_t VelodynePcapReader::dataPackets() const {
  return impl_->data_packets_;
}
const std::map<std::uint16_t, std::int64_t>& VelodynePcapReader::datagramsByPort() const {
  return impl_->ports_;
}

std::string VelodynePcapReader::imuSource() const {
  if (impl_->csv_) return "IMU CSV " + impl_->options_.imu_csv;
  return impl_->imu_from_packets_ ? "HDL-32E position packets" : "none";
}

double VelodynePcapReader::progress() const {
  if (impl_->ended_) return 1.0;
  const auto size = impl_->pcap_.fileSize();
  if (size == 0) return -1.0;
  return std::min(1.0, static_cast<double>(impl_->pcap_.bytesRead()) / static_cast<double>(size));
}

std::string VelodynePcapReader::describe() const {
  const auto& p = impl_->probe_;
  std::ostringstream text;
  text << "Velodyne pcap " << impl_->path_ << " (" << velodyne::toString(p.model) << ", "
       << velodyne::toString(static_cast<velodyne::ReturnMode>(p.return_mode));
  const double hz = rotationHz();
  if (hz > 0.0) {
    char rate[32];
    std::snprintf(rate, sizeof(rate), "%.2f", hz);
    text << ", " << rate << " Hz";
  }
  text << ", IMU: " << imuSource() << ")";
  return text.str();
}

std::unique_ptr<LogReader> openVelodynePcapLog(const std::string& path, const InputConfig& input,
                                               const SensorConfig& sensor) {
  return std::make_unique<VelodynePcapReader>(path, velodynePcapOptions(input, sensor));
}

}  // namespace storey
