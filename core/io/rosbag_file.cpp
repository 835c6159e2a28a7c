// The only file of core that includes ROS headers.
#include "io/rosbag_file.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdio>
#include <map>
#include <sstream>

#include "common/error.h"
#include "io/ros_message_codec.h"

namespace storey {
namespace {

/// The first fields of a std_msgs/Header (seq, stamp), read from the start of
/// any message whose definition begins with a Header; the rest is skipped.
struct HeaderPrefix {
  std::uint32_t seq = 0;
  std::uint32_t sec = 0;
  std::uint32_t nsec = 0;
};

}  // namespace
}  // namespace storey

namespace ros {
namespace message_traits {
template <>
struct MD5Sum<storey::HeaderPrefix> {
  static const char* value() { return "*"; }  // matches every type
  static const char* value(const storey::HeaderPrefix&) { return value(); }
};
template <>
struct DataType<storey::HeaderPrefix> {
  static const char* value() { return "*"; }
  static const char* value(const storey::HeaderPrefix&) { return value(); }
};
}  // namespace message_traits
namespace serialization {
template <>
struct Serializer<storey::HeaderPrefix> {
  template <typename Stream>
  static void read(Stream& stream, storey::HeaderPrefix& h) {
    stream.next(h.seq);
    stream.next(h.sec);
    stream.next(h.nsec);
  }
};
}  // namespace serialization
}  // namespace ros

namespace storey {
namespace {

std::int64_t toNs(const ros::Time& t) {
  return static_cast<std::int64_t>(t.toNSec());
}

}  // namespace

struct RosbagFile::Impl {
  std::string path;
  RosbagStructure structure;
  rosbag::Bag bag;
  std::vector<TopicInfo> topics;
  std::map<std::string, bool> has_header;
  std::unique_ptr<rosbag::View> view;
  rosbag::View::iterator it;
  bool started = false;
  std::map<std::string, std::int64_t> seen_per_topic;
  std::int64_t index_in_topic = -1;
  std::int64_t selection_begin_ns = 0;
  std::int64_t selection_end_ns = 0;

  const rosbag::MessageInstance& current() const {
    if (!started || !view || it == view->end()) throw Error(path + ": no current message");
    return *it;
  }

  /// Runs `body`, turning any exception into a storey::Error prefixed by `context`.
  template <typename F>
  auto guarded(const std::string& context, F&& body) const -> decltype(body()) {
    try {
      return body();
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(context + ": " + e.what());
    } catch (...) {
      throw Error(context + ": unknown failure in librosbag");
    }
  }
};

RosbagFile::RosbagFile(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->structure = checkRosbagStructure(path);
  impl_->guarded(path + ": cannot read ROS bag", [&] {
    impl_->bag.open(path, rosbag::bagmode::Read);
    rosbag::View all(impl_->bag);
    // Message counts per (topic, type) come from the index: no message is read.
    std::map<std::pair<std::string, std::string>, std::int64_t> counts;
    for (const rosbag::ConnectionInfo* c : all.getConnections()) {
      rosbag::View one(impl_->bag,
                       [id = c->id](const rosbag::ConnectionInfo* ci) { return ci->id == id; });
      counts[{c->topic, c->datatype}] += static_cast<std::int64_t>(one.size());
      auto [entry, inserted] = impl_->has_header.emplace(c->topic, false);
      if (inserted) entry->second = definitionStartsWithHeader(c->msg_def);
    }
    for (const auto& [key, count] : counts) {
      impl_->topics.push_back(TopicInfo{key.first, key.second, count});
    }
  });
}

RosbagFile::~RosbagFile() = default;

const std::string& RosbagFile::path() const {
  return impl_->path;
}
const RosbagStructure& RosbagFile::structure() const {
  return impl_->structure;
}
const std::vector<TopicInfo>& RosbagFile::topics() const {
  return impl_->topics;
}

bool RosbagFile::hasHeader(const std::string& topic) const {
  const auto it = impl_->has_header.find(topic);
  return it != impl_->has_header.end() && it->second;
}

void RosbagFile::select(const std::vector<std::string>& topics) {
  impl_->guarded(impl_->path + ": cannot read ROS bag", [&] {
    impl_->view = topics.empty()
                      ? std::make_unique<rosbag::View>(impl_->bag)
                      : std::make_unique<rosbag::View>(impl_->bag, rosbag::TopicQuery(topics));
    impl_->started = false;
    impl_->seen_per_topic.clear();
    impl_->index_in_topic = -1;
    const bool empty = impl_->view->size() == 0;
    impl_->selection_begin_ns = empty ? 0 : toNs(impl_->view->getBeginTime());
    impl_->selection_end_ns = empty ? 0 : toNs(impl_->view->getEndTime());
  });
}

std::int64_t RosbagFile::selectionBeginNs() const {
  return impl_->selection_begin_ns;
}
std::int64_t RosbagFile::selectionEndNs() const {
  return impl_->selection_end_ns;
}

bool RosbagFile::next() {
  if (!impl_->view) select({});
  return impl_->guarded(impl_->path + ": cannot read ROS bag", [&] {
    if (!impl_->started) {
      impl_->it = impl_->view->begin();
      impl_->started = true;
    } else if (impl_->it != impl_->view->end()) {
      ++impl_->it;
    }
    if (impl_->it == impl_->view->end()) return false;
    impl_->index_in_topic = impl_->seen_per_topic[impl_->it->getTopic()]++;
    return true;
  });
}

const std::string& RosbagFile::topic() const {
  return impl_->current().getTopic();
}
const std::string& RosbagFile::type() const {
  return impl_->current().getDataType();
}
std::int64_t RosbagFile::recordTimeNs() const {
  return toNs(impl_->current().getTime());
}
std::int64_t RosbagFile::indexInTopic() const {
  return impl_->index_in_topic;
}

std::string RosbagFile::where() const {
  return impl_->path + ": " + topic() + " message #" + std::to_string(indexInTopic()) +
         " (record time " + formatSecondsNs(recordTimeNs()) + " s)";
}

void RosbagFile::readPointCloud(PointCloudMessage& out) const {
  impl_->guarded(where(), [&] {
    const auto msg = impl_->current().instantiate<sensor_msgs::PointCloud2>();
    if (!msg) throw Error(where() + ": is " + type() + ", not " + kPointCloud2Type);
    out.stamp_ns = toNs(msg->header.stamp);
    out.frame_id = msg->header.frame_id;
    out.fields.clear();
    for (const auto& f : msg->fields) {
      out.fields.push_back(PointFieldDesc{f.name, f.offset, f.datatype, f.count});
    }
    out.height = msg->height;
    out.width = msg->width;
    out.point_step = msg->point_step;
    out.row_step = msg->row_step;
    out.is_bigendian = msg->is_bigendian != 0;
    out.data.swap(msg->data);
  });
}

ImuMessage RosbagFile::readImu() const {
  return impl_->guarded(where(), [&] {
    const auto msg = impl_->current().instantiate<sensor_msgs::Imu>();
    if (!msg) throw Error(where() + ": is " + type() + ", not " + kImuType);
    ImuMessage out;
    out.sample.stamp_ns = toNs(msg->header.stamp);
    out.sample.gyro = {msg->angular_velocity.x, msg->angular_velocity.y, msg->angular_velocity.z};
    out.sample.accel = {msg->linear_acceleration.x, msg->linear_acceleration.y,
                        msg->linear_acceleration.z};
    out.has_gyro = msg->angular_velocity_covariance[0] != -1.0;
    out.has_accel = msg->linear_acceleration_covariance[0] != -1.0;
    return out;
  });
}

void RosbagFile::readVelodyneScan(VelodyneScanMessage& out) const {
  impl_->guarded(where(), [&] {
    const rosbag::MessageInstance& m = impl_->current();
    std::vector<std::uint8_t> bytes(m.size());
    ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    m.write(stream);
    try {
      decodeVelodyneScan(bytes.data(), bytes.size(), WireFormat::kRos1, out);
    } catch (const Error& e) {
      throw Error(where() + ": " + e.what());
    }
  });
}

std::vector<std::pair<std::string, std::string>> RosbagFile::properties() const {
  std::string compression;
  for (const auto& [name, count] : impl_->structure.chunks_by_compression) {
    compression += (compression.empty() ? "" : "+") + name;
  }
  return {{"chunks", std::to_string(impl_->structure.chunk_count)},
          {"compression", compression.empty() ? "none" : compression}};
}

std::uint64_t RosbagFile::sizeBytes() const {
  return impl_->structure.file_size;
}

std::int64_t RosbagFile::messageCount() const {
  return static_cast<std::int64_t>(impl_->structure.message_count);
}

std::optional<std::int64_t> RosbagFile::readHeaderStamp() const {
  if (!hasHeader(topic())) return std::nullopt;
  return impl_->guarded(where(), [&]() -> std::optional<std::int64_t> {
    const auto prefix = impl_->current().instantiate<HeaderPrefix>();
    if (!prefix) return std::nullopt;
    return static_cast<std::int64_t>(prefix->sec) * 1'000'000'000 + prefix->nsec;
  });
}

}  // namespace storey
