#include "io/log_summary.h"

#include <algorithm>
#include <limits>
#include <map>

#include "common/error.h"
#include "common/time.h"
#include "io/log_format.h"
#include "io/rosbag_file.h"
#include "io/topic_selection.h"

namespace storey {
namespace {

/// Accumulates one topic's statistics while the log is read.
struct TopicAccumulator {
  TopicSummary summary;
  std::vector<std::int64_t> points_per_message;
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

}  // namespace

double TopicSummary::durationSeconds() const {
  return nsToSeconds(last_stamp_ns - first_stamp_ns);
}

double TopicSummary::rateHz() const {
  const double duration = durationSeconds();
  return count > 1 && duration > 0.0 ? static_cast<double>(count - 1) / duration : 0.0;
}

LogSummary summarizeLog(const std::string& path, const InputConfig& input,
                        const ProgressFn& progress) {
  if (detectLogFormat(path) != LogFormat::kRosbag1) throw Error(path + ": unknown log format");
  RosbagFile bag(path);

  LogSummary out;
  out.path = path;
  out.format = "ROS1 bag 2.0";
  out.size_bytes = bag.structure().file_size;
  out.compression = compressionOf(bag.structure());
  out.chunks = bag.structure().chunk_count;
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

  const double total =
      static_cast<double>(std::max<std::uint64_t>(1, bag.structure().message_count));
  bool have_record = false;
  PointCloudMessage cloud;
  bag.select({});
  while (bag.next()) {
    auto& acc = topics[{bag.topic(), bag.type()}];
    ++acc.summary.count;
    ++out.messages;
    const std::int64_t record_ns = bag.recordTimeNs();
    out.start_ns = have_record ? std::min(out.start_ns, record_ns) : record_ns;
    out.end_ns = have_record ? std::max(out.end_ns, record_ns) : record_ns;
    have_record = true;

    if (bag.type() == kPointCloud2Type) {
      bag.readPointCloud(cloud);
      acc.addCloud(cloud);
      acc.addStamp(cloud.stamp_ns);
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
  if (progress) progress(1.0, "reading log");
  return out;
}

}  // namespace storey
