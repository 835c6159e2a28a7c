#include "sim/ros2_bag_writer.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "io/ros_message_codec.h"
#include "io/rosbag2_metadata.h"
#include "sim/cloud_messages.h"
#include "sim/db3_writer.h"

namespace storey::sim {
namespace {

/// "sensor_msgs/PointCloud2" -> "sensor_msgs/msg/PointCloud2".
std::string ros2Type(const std::string& canonical) {
  const auto slash = canonical.find('/');
  return canonical.substr(0, slash) + "/msg" + canonical.substr(slash);
}

}  // namespace

Ros2BagWriter::Ros2BagWriter(const std::string& dir, Ros2Storage storage,
                             const McapWriterOptions& mcap)
    : dir_(dir), storage_(storage) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw Error(dir_ + ": cannot create the folder: " + ec.message());
  const std::string stem = std::filesystem::path(dir_).filename().string();
  file_name_ = stem + "_0" + (storage_ == Ros2Storage::kSqlite3 ? ".db3" : ".mcap");
  const std::string file = (std::filesystem::path(dir_) / file_name_).string();
  writer_ = storage_ == Ros2Storage::kSqlite3 ? openDb3Writer(file) : openMcapWriter(file, mcap);
}

Ros2BagWriter::~Ros2BagWriter() = default;

void Ros2BagWriter::write(const std::string& topic, const char* canonical_type,
                          std::int64_t log_time_ns, const std::vector<std::uint8_t>& data) {
  auto [it, inserted] = topics_.emplace(topic, TopicState{});
  TopicState& t = it->second;
  if (inserted) {
    t.id = static_cast<int>(topics_.size());
    t.type = ros2Type(canonical_type);
    writer_->addTopic(t.id, topic, t.type, rosMessageDefinition(canonical_type, WireFormat::kCdr));
  }
  writer_->write(t.id, log_time_ns, data);
  ++t.count;
  first_ns_ = messages_ == 0 ? log_time_ns : std::min(first_ns_, log_time_ns);
  last_ns_ = messages_ == 0 ? log_time_ns : std::max(last_ns_, log_time_ns);
  ++messages_;
}

void Ros2BagWriter::writeScan(const std::string& topic, const Scan& scan, std::int64_t receipt_ns) {
  write(topic, kPointCloud2Type, receipt_ns,
        encodePointCloud2(velodyneLayoutCloud(scan), WireFormat::kCdr));
}

void Ros2BagWriter::writeOrganisedScan(const std::string& topic, const std::string& frame_id,
                                       const OrganisedScan& scan, std::int64_t stamp_ns,
                                       std::int64_t receipt_ns) {
  write(topic, kPointCloud2Type, receipt_ns,
        encodePointCloud2(ousterLayoutCloud(scan, frame_id, stamp_ns), WireFormat::kCdr));
}

void Ros2BagWriter::writeImu(const std::string& topic, const std::string& frame_id,
                             const ImuSample& sample, std::int64_t record_ns, double gyro_variance,
                             double accel_variance, const ImuOrientation* orientation) {
  double q[4], variance[3];
  if (orientation != nullptr) {
    const Eigen::Quaterniond& o = orientation->q_world_imu;
    q[0] = o.x(), q[1] = o.y(), q[2] = o.z(), q[3] = o.w();
    for (int i = 0; i < 3; ++i) variance[i] = orientation->variance[i];
  }
  write(topic, kImuType, record_ns,
        encodeImu(sample, frame_id, gyro_variance, accel_variance, orientation ? q : nullptr,
                  orientation ? variance : nullptr, WireFormat::kCdr));
}

void Ros2BagWriter::writeVelodyneScan(const std::string& topic, const VelodyneScanMessage& scan,
                                      std::int64_t receipt_ns) {
  write(topic, kVelodyneScanType, receipt_ns, encodeVelodyneScan(scan, WireFormat::kCdr));
}

void Ros2BagWriter::close() {
  if (closed_) return;
  closed_ = true;
  writer_->close();
  const char* storage = storage_ == Ros2Storage::kSqlite3 ? "sqlite3" : "mcap";
  std::ostringstream y;
  y << "rosbag2_bagfile_information:\n"
    << "  version: 5\n"
    << "  storage_identifier: " << storage << "\n"
    << "  duration:\n    nanoseconds: " << (last_ns_ - first_ns_) << "\n"
    << "  starting_time:\n    nanoseconds_since_epoch: " << first_ns_ << "\n"
    << "  message_count: " << messages_ << "\n"
    << "  topics_with_message_count:\n";
  for (const auto& [name, t] : topics_) {
    y << "    - topic_metadata:\n"
      << "        name: " << name << "\n"
      << "        type: " << t.type << "\n"
      << "        serialization_format: cdr\n"
      << "        offered_qos_profiles: \"\"\n"
      << "      message_count: " << t.count << "\n";
  }
  y << "  compression_format: \"\"\n"
    << "  compression_mode: \"\"\n"
    << "  relative_file_paths:\n    - " << file_name_ << "\n"
    << "  files:\n    - path: " << file_name_ << "\n"
    << "      starting_time:\n        nanoseconds_since_epoch: " << first_ns_ << "\n"
    << "      duration:\n        nanoseconds: " << (last_ns_ - first_ns_) << "\n"
    << "      message_count: " << messages_ << "\n";
  writeFileAtomically((std::filesystem::path(dir_) / kRosbag2MetadataFile).string(), y.str());
}

}  // namespace storey::sim
