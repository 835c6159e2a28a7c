#include "io/rosbag_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "common/log.h"
#include "io/message_sequencer.h"
#include "io/point_cloud_to_scan.h"
#include "io/ros2_bag.h"
#include "io/rosbag_file.h"
#include "io/topic_selection.h"
#include "io/velodyne/velodyne_scan_decoder.h"

namespace storey {
namespace {

/// Key of LogReadStats::dropped for messages of a selected topic recorded with another type.
constexpr const char* kDropOtherType = "message_of_other_type";
/// Stamp-to-record-time latencies of the two streams farther apart than this
/// suggest that the LiDAR and the IMU stamp with different clocks.
constexpr double kClockMismatchS = 1.0;

/// Any ROS log (ROS1 bag, rosbag2, MCAP): point clouds or Velodyne packets and IMU.
class RosLogReader final : public LogReader {
 public:
  RosLogReader(std::unique_ptr<RosMessageSource> source, const InputConfig& input,
               const SensorConfig& sensor)
      : source_(std::move(source)),
        bag_(*source_),
        topics_(chooseTopics(bag_.topics(), input, bag_.path())),
        clouds_(topics_.points_topic, sensor.lidar_model,
                PointFilter{input.min_range, input.max_range}),
        sequencer_(sequencerOptions(sensor), stats_),
        offset_ns_(secondsToNs(sensor.time_offset_lidar_to_imu)) {
    if (topics_.points_type == kVelodyneScanType) {
      packets_ = std::make_unique<VelodyneScanDecoder>(bag_.path() + ": " + topics_.points_topic,
                                                       velodyneScanOptions(input));
    }
    bag_.select({topics_.points_topic, topics_.imu_topic});
  }

  bool next(LogMessage& message) override {
    while (!sequencer_.pop(message)) {
      if (ended_) return false;
      if (!readOne()) {
        ended_ = true;
        if (packets_) {
          std::vector<Scan> done;
          packets_->flush(done);
          for (auto& scan : done) pushScan(std::move(scan), false);
        }
        sequencer_.finish();
      }
    }
    return true;
  }

  const LogReadStats& stats() const override { return stats_; }

  double progress() const override {
    if (ended_) return 1.0;
    if (!started_) return 0.0;
    const std::int64_t span = bag_.selectionEndNs() - bag_.selectionBeginNs();
    if (span <= 0) return 0.0;
    const double done = static_cast<double>(last_record_ns_ - bag_.selectionBeginNs()) / span;
    return std::min(1.0, std::max(0.0, done));
  }

  std::string describe() const override {
    std::string lidar = topics_.points_topic;
    if (packets_ && packets_->started()) {
      lidar += std::string(": ") + velodyne::toString(packets_->model()) + " packets";
    }
    return bag_.formatName() + " " + bag_.path() + " (" + lidar + ", " + topics_.imu_topic + ")";
  }

 private:
  static MessageSequencer::Options sequencerOptions(const SensorConfig& sensor) {
    MessageSequencer::Options options;
    options.lidar_to_imu_offset_ns = secondsToNs(sensor.time_offset_lidar_to_imu);
    return options;
  }

  /// Reads one message of the bag into the sequencer; false at the end of the bag.
  bool readOne() {
    if (!bag_.next()) return false;
    started_ = true;
    last_record_ns_ = bag_.recordTimeNs();
    const bool is_points = bag_.topic() == topics_.points_topic;
    if (canonicalRosType(bag_.type()) != (is_points ? topics_.points_type : kImuType)) {
      ++stats_.dropped[kDropOtherType];
      return true;
    }
    if (is_points && packets_) {
      bag_.readVelodyneScan(packet_scan_);
      std::vector<Scan> done;
      try {
        packets_->add(packet_scan_, done, stats_.dropped);
      } catch (const Error& e) {
        throw Error(bag_.where() + ": " + e.what());
      }
      for (auto& scan : done) {
        if (scan.frame_id.empty()) scan.frame_id = packet_scan_.frame_id;
        pushScan(std::move(scan));
      }
    } else if (is_points) {
      bag_.readPointCloud(cloud_);
      Scan scan;
      try {
        scan = clouds_.convert(cloud_.view(), cloud_.stamp_ns, cloud_.frame_id, stats_.dropped);
      } catch (const Error& e) {
        throw Error(bag_.where() + ": " + e.what());
      }
      pushScan(std::move(scan));
    } else {
      const ImuMessage imu = bag_.readImu();
      if (!imu.has_gyro || !imu.has_accel) {
        ++stats_.dropped[kDropImuMissingData];
        return true;
      }
      checkClocks(imu.sample.stamp_ns, false);
      sequencer_.push(imu.sample);
    }
    return true;
  }

  /// `check_clock`: a message is current (its record time is known).
  void pushScan(Scan&& scan, bool check_clock = true) {
    if (check_clock) checkClocks(scan.stamp_ns + offset_ns_, true);
    sequencer_.push(std::move(scan));
  }

  /// Warns once when the two streams' stamps run on clearly different clocks.
  void checkClocks(std::int64_t stamp_ns, bool is_scan) {
    auto& latency = is_scan ? scan_latency_s_ : imu_latency_s_;
    if (std::isnan(latency)) latency = nsToSeconds(bag_.recordTimeNs() - stamp_ns);
    if (clock_checked_ || std::isnan(scan_latency_s_) || std::isnan(imu_latency_s_)) return;
    clock_checked_ = true;
    const double gap = scan_latency_s_ - imu_latency_s_;
    if (std::abs(gap) > kClockMismatchS) {
      char text[64];
      std::snprintf(text, sizeof(text), "%.3f", gap);
      logWarning(bag_.path() + ": point cloud stamps and IMU stamps differ by about " + text +
                 " s relative to the record times: different clocks? (set "
                 "sensor.time_offset_lidar_to_imu; stamps are used as recorded)");
    }
  }

  std::unique_ptr<RosMessageSource> source_;
  RosMessageSource& bag_;
  TopicChoice topics_;
  std::unique_ptr<VelodyneScanDecoder> packets_;  ///< when the LiDAR topic holds packets
  VelodyneScanMessage packet_scan_;               ///< reused between messages
  PointCloudToScan clouds_;
  LogReadStats stats_;
  MessageSequencer sequencer_;
  PointCloudMessage cloud_;  ///< reused between clouds
  std::int64_t offset_ns_;   ///< LiDAR to IMU clock [ns]
  bool ended_ = false;
  bool started_ = false;
  std::int64_t last_record_ns_ = 0;  ///< record time of the last message read
  double scan_latency_s_ = std::nan("");
  double imu_latency_s_ = std::nan("");
  bool clock_checked_ = false;
};

}  // namespace

std::unique_ptr<LogReader> openRosLog(std::unique_ptr<RosMessageSource> source,
                                      const InputConfig& input, const SensorConfig& sensor) {
  return std::make_unique<RosLogReader>(std::move(source), input, sensor);
}

std::unique_ptr<LogReader> openRosbagLog(const std::string& path, const InputConfig& input,
                                         const SensorConfig& sensor) {
  return openRosLog(std::make_unique<RosbagFile>(path), input, sensor);
}

std::unique_ptr<LogReader> openRos2Log(const std::string& path, const InputConfig& input,
                                       const SensorConfig& sensor) {
  return openRosLog(openRos2Bag(path), input, sensor);
}

}  // namespace storey
