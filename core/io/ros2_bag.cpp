#include "io/ros2_bag.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>

#include "common/error.h"
#include "io/mcap_file.h"
#include "io/ros_message_codec.h"
#include "io/rosbag2_metadata.h"
#include "io/sqlite_storage.h"

namespace storey {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> filesWithExtension(const std::string& dir, const std::string& ext) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ext) {
      out.push_back(entry.path().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string firstBytes(const std::string& path, std::size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string head(n, '\0');
  in.read(head.data(), static_cast<std::streamsize>(n));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
  return head;
}

/// The storage of the bag at `path` and the name of its format.
std::unique_ptr<MessageStorage> openStorage(const std::string& path, std::string& format) {
  if (!fs::is_directory(path)) {
    const std::string head = firstBytes(path, 16);
    if (isMcapMagic(head)) {
      format = "MCAP";
      return openMcapStorage(path);
    }
    format = "rosbag2 (sqlite3)";
    return openSqliteStorage({path});
  }
  const fs::path metadata_path = fs::path(path) / kRosbag2MetadataFile;
  std::vector<std::string> files;
  std::string storage;
  if (fs::exists(metadata_path)) {
    const Rosbag2Metadata metadata = readRosbag2Metadata(metadata_path.string());
    if (!metadata.compression_mode.empty() && metadata.compression_mode != "NONE") {
      throw Error(metadata_path.string() + ": the bag is compressed (compression_mode " +
                  metadata.compression_mode + ", " + metadata.compression_format +
                  "): Storey reads uncompressed rosbag2 files (MCAP chunk compression is "
                  "fine); decompress it with `ros2 bag decompress` or re-record with MCAP");
    }
    storage = metadata.storage_identifier;
    for (const auto& relative : metadata.relative_file_paths) {
      const fs::path file = fs::path(path) / relative;
      if (!fs::exists(file)) {
        throw Error(metadata_path.string() + ": lists " + relative + ", which is missing from " +
                    path);
      }
      files.push_back(file.string());
    }
    if (files.empty()) throw Error(metadata_path.string() + ": lists no bag file (empty bag)");
  } else {
    files = filesWithExtension(path, ".db3");
    storage = "sqlite3";
    if (files.empty()) {
      files = filesWithExtension(path, ".mcap");
      storage = "mcap";
    }
    if (files.empty()) throw Error(path + ": no metadata.yaml, .db3 or .mcap file in the folder");
  }
  if (storage == "sqlite3") {
    format = "rosbag2 (sqlite3)";
    return openSqliteStorage(files);
  }
  if (storage == "mcap") {
    if (files.size() > 1) {
      throw Error(path + ": a split MCAP bag (" + std::to_string(files.size()) +
                  " files) is not supported; give one of its .mcap files");
    }
    format = "rosbag2 (MCAP)";
    return openMcapStorage(files.front());
  }
  throw Error(metadata_path.string() + ": storage '" + storage +
              "' is not supported (Storey reads sqlite3 and mcap)");
}

class Ros2Bag final : public RosMessageSource {
 public:
  explicit Ros2Bag(const std::string& path) : path_(path) {
    storage_ = openStorage(path, format_);
    for (const auto& t : storage_->topics()) {
      topics_.push_back(TopicInfo{t.name, t.type, t.count});
      const std::string canonical = canonicalRosType(t.type);
      const bool known =
          canonical == kPointCloud2Type || canonical == kImuType || canonical == kVelodyneScanType;
      has_header_[t.name] = known || definitionStartsWithHeader(t.definition);
    }
    std::sort(topics_.begin(), topics_.end(),
              [](const TopicInfo& a, const TopicInfo& b) { return a.name < b.name; });
  }

  const std::string& path() const override { return path_; }
  std::string formatName() const override { return format_; }
  std::vector<std::pair<std::string, std::string>> properties() const override {
    return storage_->properties();
  }
  std::uint64_t sizeBytes() const override { return storage_->sizeBytes(); }
  const std::vector<TopicInfo>& topics() const override { return topics_; }
  bool hasHeader(const std::string& topic) const override {
    const auto it = has_header_.find(topic);
    return it != has_header_.end() && it->second;
  }

  void select(const std::vector<std::string>& topics) override {
    std::vector<bool> wanted;
    if (!topics.empty()) {
      const auto& all = storage_->topics();
      wanted.assign(all.size(), false);
      for (std::size_t i = 0; i < all.size(); ++i) {
        wanted[i] = std::find(topics.begin(), topics.end(), all[i].name) != topics.end();
      }
    }
    storage_->select(wanted);
    seen_.clear();
    have_current_ = false;
  }

  bool next() override {
    if (!storage_->next(current_)) {
      have_current_ = false;
      return false;
    }
    have_current_ = true;
    index_in_topic_ = seen_[current_.topic]++;
    return true;
  }

  std::int64_t selectionBeginNs() const override { return storage_->beginNs(); }
  std::int64_t selectionEndNs() const override { return storage_->endNs(); }

  const std::string& topic() const override { return info().name; }
  const std::string& type() const override { return info().type; }
  std::int64_t recordTimeNs() const override { return current_.log_time_ns; }
  std::int64_t indexInTopic() const override { return index_in_topic_; }
  std::string where() const override {
    return path_ + ": " + topic() + " message #" + std::to_string(index_in_topic_) +
           " (record time " + formatSecondsNs(recordTimeNs()) + " s)";
  }

  void readPointCloud(PointCloudMessage& out) const override {
    decode(kPointCloud2Type, [&](WireFormat f) {
      decodePointCloud2(current_.data.data(), current_.data.size(), f, out);
    });
  }
  ImuMessage readImu() const override {
    ImuMessage out;
    decode(kImuType,
           [&](WireFormat f) { out = decodeImu(current_.data.data(), current_.data.size(), f); });
    return out;
  }
  void readVelodyneScan(VelodyneScanMessage& out) const override {
    decode(kVelodyneScanType, [&](WireFormat f) {
      decodeVelodyneScan(current_.data.data(), current_.data.size(), f, out);
    });
  }
  std::optional<std::int64_t> readHeaderStamp() const override {
    if (!hasHeader(topic())) return std::nullopt;
    std::optional<std::int64_t> stamp;
    decode(nullptr, [&](WireFormat f) {
      stamp = decodeHeaderStamp(current_.data.data(), current_.data.size(), f);
    });
    return stamp;
  }

 private:
  const StorageTopic& info() const {
    if (!have_current_) throw Error(path_ + ": no current message");
    return storage_->topics()[current_.topic];
  }

  /// Runs `body` with the topic's wire format, prefixing errors with where().
  template <typename F>
  void decode(const char* expected_type, F&& body) const {
    const StorageTopic& t = info();
    if (expected_type != nullptr && canonicalRosType(t.type) != expected_type) {
      throw Error(where() + ": is " + t.type + ", not " + expected_type);
    }
    WireFormat format;
    if (t.encoding == "cdr") {
      format = WireFormat::kCdr;
    } else if (t.encoding == "ros1") {
      format = WireFormat::kRos1;
    } else {
      throw Error(where() + ": message encoding '" + t.encoding +
                  "' is not supported (Storey reads cdr and ros1)");
    }
    try {
      body(format);
    } catch (const Error& e) {
      throw Error(where() + ": " + e.what());
    }
  }

  std::string path_;
  std::string format_;
  std::unique_ptr<MessageStorage> storage_;
  std::vector<TopicInfo> topics_;
  std::map<std::string, bool> has_header_;
  RawMessage current_;
  bool have_current_ = false;
  std::map<std::size_t, std::int64_t> seen_;
  std::int64_t index_in_topic_ = 0;
};

}  // namespace

bool isRos2BagFolder(const std::string& dir) {
  if (fs::exists(fs::path(dir) / kRosbag2MetadataFile)) return true;
  return !filesWithExtension(dir, ".db3").empty() || !filesWithExtension(dir, ".mcap").empty();
}

std::unique_ptr<RosMessageSource> openRos2Bag(const std::string& path) {
  return std::make_unique<Ros2Bag>(path);
}

}  // namespace storey
