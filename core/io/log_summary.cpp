#include "io/log_summary.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>

#include "common/error.h"
#include "common/time.h"
#include "io/imu_csv.h"
#include "io/log_format.h"
#include "io/pcd_file.h"
#include "io/pcd_folder_reader.h"
#include "io/ros2_bag.h"
#include "io/rosbag_file.h"
#include "io/topic_selection.h"
#include "io/velodyne/pcap_file.h"
#include "io/velodyne/velodyne_pcap_reader.h"
#include "io/velodyne/velodyne_scan_decoder.h"

namespace storey {
namespace {

/// Accumulates one topic's statistics while the log is read.
struct TopicAccumulator {
  TopicSummary summary;
  std::vector<std::int64_t> points_per_message;  ///< VelodyneScan topics: packets per message
  std::map<std::string, std::int64_t> packet_drops;
  bool have_stamp = false;

  void addStamp(std::int64_t stamp_ns) {
    if (!have_stamp) {
      summary.first_stamp_ns = summary.last_stamp_ns = stamp_ns;
      have_stamp = true;
    }
    summary.first_stamp_ns = std::min(summary.first_stamp_ns, stamp_ns);
    summary.last_stamp_ns = std::max(summary.last_stamp_ns, stamp_ns);
  }

  void addCloud(const PointCloudMessage& cloud) {
    if (points_per_message.empty()) {
      summary.fields = cloud.fields;
      summary.point_step = cloud.point_step;
    } else if (cloud.fields != summary.fields || cloud.point_step != summary.point_step) {
      summary.layout_varies = true;
    }
    points_per_message.push_back(static_cast<std::int64_t>(cloud.width) * cloud.height);
  }

  TopicSummary finish() {
    if (!points_per_message.empty()) {
      auto& v = points_per_message;
      std::sort(v.begin(), v.end());
      summary.points_min = v.front();
      summary.points_max = v.back();
      summary.points_median = v[v.size() / 2];
    }
    return summary;
  }
};

std::string compressionOf(const RosbagStructure& structure) {
  std::string text;
  for (const auto& [name, count] : structure.chunks_by_compression) {
    text += (text.empty() ? "" : "+") + name;
  }
  return text.empty() ? "none" : text;
}

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

/// Reads every message of `reader` into a scan stream and an IMU stream.
void summarizeStreams(LogReader& reader, const std::string& scan_name, const std::string& imu_name,
                      LogSummary& out, const ProgressFn& progress) {
  TopicAccumulator scans, imu;
  scans.summary.name = scan_name;
  scans.summary.type = "scan";
  scans.summary.header_stamps = true;
  imu.summary.name = imu_name;
  imu.summary.type = "imu";
  imu.summary.header_stamps = true;
  LogMessage message;
  while (reader.next(message)) {
    ++out.messages;
    if (const auto* scan = std::get_if<Scan>(&message)) {
      ++scans.summary.count;
      scans.addStamp(scan->stamp_ns);
      scans.points_per_message.push_back(static_cast<std::int64_t>(scan->points.size()));
    } else {
      ++imu.summary.count;
      imu.addStamp(std::get<ImuSample>(message).stamp_ns);
    }
    if (progress && out.messages % 64 == 0 &&
        !progress(std::max(0.0, reader.progress()), "reading log")) {
      throw Cancelled();
    }
  }
  bool have = false;
  for (auto* acc : {&scans, &imu}) {
    if (acc->summary.count == 0) continue;
    out.start_ns =
        have ? std::min(out.start_ns, acc->summary.first_stamp_ns) : acc->summary.first_stamp_ns;
    out.end_ns =
        have ? std::max(out.end_ns, acc->summary.last_stamp_ns) : acc->summary.last_stamp_ns;
    have = true;
  }
  out.topics.push_back(scans.finish());
  if (imu.summary.count > 0 || !imu_name.empty()) out.topics.push_back(imu.finish());
  for (const auto& [reason, count] : reader.stats().dropped) {
    if (count > 0) out.dropped[reason] = count;
  }
  if (progress) progress(1.0, "reading log");
}

LogSummary summarizePcap(const std::string& path, const InputConfig& input,
                         const SensorConfig& sensor, const ProgressFn& progress) {
  LogSummary out;
  out.path = path;
  out.format = "Velodyne pcap";
  std::error_code ec;
  out.size_bytes = std::filesystem::file_size(path, ec);
  VelodynePcapOptions options = velodynePcapOptions(input, sensor);
  options.require_imu = false;
  VelodynePcapReader reader(path, options);
  const VelodyneProbe& probe = reader.probe();
  out.properties.push_back(
      {"sensor", std::string(velodyne::toString(probe.model)) +
                     (probe.model_from_product_id ? " (product id "
                                                  : " (from the packet period; product id ") +
                     velodyne::hexByte(probe.product) + ")"});
  out.properties.push_back(
      {"return mode", velodyne::toString(static_cast<velodyne::ReturnMode>(probe.return_mode))});
  summarizeStreams(
      reader, "scans (UDP " + std::to_string(options.data_port) + " data packets)",
      reader.imuSource() == "none" ? std::string() : "IMU (" + reader.imuSource() + ")", out,
      progress);
  out.properties.push_back({"rotation", fixed(reader.rotationHz(), 2) + " Hz (" +
                                            fixed(reader.rotationHz() * 60.0, 0) + " rpm)"});
  out.properties.push_back({"data packets", std::to_string(reader.dataPackets())});
  std::string ports;
  for (const auto& [port, count] : reader.datagramsByPort()) {
    ports +=
        (ports.empty() ? "" : ", ") + std::to_string(count) + " to port " + std::to_string(port);
  }
  out.properties.push_back({"UDP datagrams", ports.empty() ? "none" : ports});
  out.properties.push_back({"IMU", reader.imuSource()});
  out.points_topic = out.topics.front().name;
  out.imu_topic = reader.imuSource() == "none" ? "" : reader.imuSource();
  if (out.topics.front().count == 0) {
    out.input_problem = "no scan could be decoded";
  } else if (out.imu_topic.empty()) {
    out.input_problem = path +
                        ": no IMU: the capture holds no HDL-32E position packet with IMU "
                        "values; give an IMU CSV (input.imu_csv, --imu-csv)";
  }
  return out;
}

LogSummary summarizePcdFolder(const std::string& path, const InputConfig& input,
                              const SensorConfig& sensor, const ProgressFn& progress) {
  LogSummary out;
  out.path = path;
  out.format = "PCD folder";
  const auto scans = findPcdScans(path);
  std::uint64_t bytes = 0;
  std::error_code ec;
  for (const auto& s : scans) bytes += std::filesystem::file_size(s.path, ec);
  out.size_bytes = bytes;
  const PcdHeader header = readPcdHeader(scans.front().path);
  std::string fields;
  for (const auto& f : header.fields) fields += (fields.empty() ? "" : " ") + f.name;
  out.properties.push_back(
      {"PCD files", std::to_string(scans.size()) + " (first: " +
                        std::filesystem::path(scans.front().path).filename().string() + ", DATA " +
                        header.data + ")"});
  out.properties.push_back({"fields", fields});
  out.properties.push_back(
      {"scan times", std::filesystem::exists(std::filesystem::path(path) / kPcdListFile)
                         ? std::string("from ") + kPcdListFile
                         : std::string("from the file names")});
  const std::string csv = pcdFolderImuCsv(path, input);
  out.properties.push_back({"IMU", csv.empty() ? "none" : "IMU CSV " + csv});
  auto reader = openPcdFolderLog(path, input, sensor, false);
  summarizeStreams(*reader, "scans (PCD files)", csv.empty() ? "" : "IMU (" + csv + ")", out,
                   progress);
  TopicSummary& t = out.topics.front();
  t.fields = header.fields;
  t.point_step = header.point_step;
  out.points_topic = t.name;
  out.imu_topic = csv;
  if (csv.empty()) {
    out.input_problem = path + ": no IMU: put the IMU CSV in the folder as " +
                        std::string(kPcdFolderImuCsv) +
                        " or give it with input.imu_csv (--imu-csv)";
  }
  return out;
}

}  // namespace

double TopicSummary::durationSeconds() const {
  return nsToSeconds(last_stamp_ns - first_stamp_ns);
}

double TopicSummary::rateHz() const {
  const double duration = durationSeconds();
  return count > 1 && duration > 0.0 ? static_cast<double>(count - 1) / duration : 0.0;
}

LogSummary summarizeLog(const std::string& path, const InputConfig& input,
                        const SensorConfig& sensor, const ProgressFn& progress) {
  switch (detectLogFormat(path)) {
    case LogFormat::kVelodynePcap:
      return summarizePcap(path, input, sensor, progress);
    case LogFormat::kPcdFolder:
      return summarizePcdFolder(path, input, sensor, progress);
    case LogFormat::kRosbag1:
    case LogFormat::kRos2Sqlite:
    case LogFormat::kMcap:
      break;
  }
  return summarizeLog(path, input, progress);
}

LogSummary summarizeLog(const std::string& path, const InputConfig& input,
                        const ProgressFn& progress) {
  const LogFormat format = detectLogFormat(path);
  if (format == LogFormat::kVelodynePcap || format == LogFormat::kPcdFolder) {
    return summarizeLog(path, input, SensorConfig{}, progress);
  }
  std::unique_ptr<RosMessageSource> source;
  if (format == LogFormat::kRosbag1) {
    auto rosbag = std::make_unique<RosbagFile>(path);
    source = std::move(rosbag);
  } else {
    source = openRos2Bag(path);
  }
  RosMessageSource& bag = *source;

  LogSummary out;
  out.path = path;
  out.format = bag.formatName();
  out.ros = true;
  out.size_bytes = bag.sizeBytes();
  if (format == LogFormat::kRosbag1) {
    const auto& structure = static_cast<RosbagFile&>(bag).structure();
    out.compression = compressionOf(structure);
    out.chunks = structure.chunk_count;
  }
  try {
    const TopicChoice choice = chooseTopics(bag.topics(), input, path);
    out.points_topic = choice.points_topic;
    out.imu_topic = choice.imu_topic;
  } catch (const Error& e) {
    out.input_problem = e.what();
  }

  std::map<std::pair<std::string, std::string>, TopicAccumulator> topics;
  for (const auto& t : bag.topics()) {
    auto& acc = topics[{t.name, t.type}];
    acc.summary.name = t.name;
    acc.summary.type = t.type;
    acc.summary.header_stamps = bag.hasHeader(t.name);
  }

  const double total = static_cast<double>(std::max<std::int64_t>(1, bag.messageCount()));
  bool have_record = false;
  PointCloudMessage cloud;
  VelodyneScanMessage packets;
  // Packet topics: the model and return mode from the first packets.
  std::map<std::string, std::unique_ptr<VelodyneScanDecoder>> decoders;
  auto velodyne = [&](const std::string& topic) -> VelodyneScanDecoder& {
    auto& d = decoders[topic];
    if (!d)
      d = std::make_unique<VelodyneScanDecoder>(path + ": " + topic, velodyneScanOptions(input));
    return *d;
  };
  bag.select({});
  while (bag.next()) {
    auto& acc = topics[{bag.topic(), bag.type()}];
    ++acc.summary.count;
    ++out.messages;
    const std::int64_t record_ns = bag.recordTimeNs();
    out.start_ns = have_record ? std::min(out.start_ns, record_ns) : record_ns;
    out.end_ns = have_record ? std::max(out.end_ns, record_ns) : record_ns;
    have_record = true;

    const std::string type = canonicalRosType(bag.type());
    if (type == kPointCloud2Type) {
      bag.readPointCloud(cloud);
      acc.addCloud(cloud);
      acc.addStamp(cloud.stamp_ns);
    } else if (type == kVelodyneScanType) {
      bag.readVelodyneScan(packets);
      acc.addStamp(packets.stamp_ns);
      std::vector<Scan> done;
      velodyne(bag.topic()).add(packets, done, acc.packet_drops);
      acc.points_per_message.push_back(static_cast<std::int64_t>(packets.packets.size()));
    } else if (acc.summary.header_stamps) {
      const auto stamp = bag.readHeaderStamp();
      acc.addStamp(stamp ? *stamp : record_ns);
    } else {
      acc.addStamp(record_ns);
    }
    if (progress && out.messages % 1000 == 0 &&
        !progress(static_cast<double>(out.messages) / total, "reading log")) {
      throw Cancelled();
    }
  }
  for (auto& [key, acc] : topics) out.topics.push_back(acc.finish());
  for (const auto& [name, value] : bag.properties()) out.properties.push_back({name, value});
  for (const auto& [topic, decoder] : decoders) {
    if (!decoder->started()) continue;
    out.properties.push_back(
        {topic,
         std::string(velodyne::toString(decoder->model())) + " packets" +
             (decoder->detection().from_product_id ? " (product id "
                                                   : " (from the packet period; product id ") +
             velodyne::hexByte(decoder->product()) + "), " +
             velodyne::toString(static_cast<velodyne::ReturnMode>(decoder->returnMode())) + ", " +
             std::to_string(decoder->packets()) + " packets"});
  }
  if (progress) progress(1.0, "reading log");
  return out;
}

}  // namespace storey
