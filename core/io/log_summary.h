#pragma once
/// What a log holds, topic by topic: the body of `storey info`. Works on any
/// ROS1 bag, including topics Storey does not read, on Velodyne captures and
/// on PCD folders (their streams decoded as a run would decode them).
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/progress.h"
#include "io/input_config.h"
#include "io/point_cloud_layout.h"
#include "types/sensor.h"

namespace storey {

struct TopicSummary {
  std::string name;
  std::string type;                 ///< e.g. "sensor_msgs/Imu"
  std::int64_t count = 0;           ///< messages
  bool header_stamps = false;       ///< stamps are header stamps; else record times (no header)
  std::int64_t first_stamp_ns = 0;  ///< earliest stamp [ns]
  std::int64_t last_stamp_ns = 0;   ///< latest stamp [ns]
  double durationSeconds() const;   ///< last - first [s]
  double rateHz() const;            ///< (count - 1) / duration [Hz]; 0 when undefined

  // sensor_msgs/PointCloud2 topics only (VelodyneScan topics: packets per message in points_*).
  std::vector<PointFieldDesc> fields;  ///< of the first message
  std::uint32_t point_step = 0;        ///< of the first message [bytes]
  bool layout_varies = false;          ///< some message has other fields or point_step
  std::int64_t points_min = 0;         ///< width x height per message
  std::int64_t points_median = 0;
  std::int64_t points_max = 0;
};

struct LogSummary {
  std::string path;
  std::string format;  ///< e.g. "ROS1 bag 2.0", "rosbag2 (sqlite3)", "MCAP"
  bool ros = false;    ///< a log of ROS topics (ROS1 bag, rosbag2, MCAP)
  std::uint64_t size_bytes = 0;
  std::string compression;  ///< chunk compression(s), e.g. "none", "lz4", "none+lz4"
  std::uint32_t chunks = 0;
  std::int64_t messages = 0;
  std::int64_t start_ns = 0;         ///< earliest record time [ns]
  std::int64_t end_ns = 0;           ///< latest record time [ns]
  std::vector<TopicSummary> topics;  ///< sorted by name

  // Velodyne pcap and PCD folder logs (empty for bags): what the reader found,
  // as (name, value) lines, and what it skipped by reason. Their streams are
  // listed in `topics` (type "scan" with point counts, or "imu").
  std::vector<std::pair<std::string, std::string>> properties;
  std::map<std::string, std::int64_t> dropped;

  std::string points_topic;   ///< the point cloud topic a run would read; empty when none
  std::string imu_topic;      ///< the IMU topic a run would read; empty when none
  std::string input_problem;  ///< why a run could not read the log; empty when it can
};

/// Reads every message of the log (one at a time) and summarises it; topics
/// are chosen as a run would choose them with `input`. Throws storey::Error
/// naming the file for a file that cannot be read, storey::Cancelled when
/// `progress` returns false.
LogSummary summarizeLog(const std::string& path, const InputConfig& input,
                        const ProgressFn& progress = {});
/// The same with the whole configuration (sensor.lidar_model and
/// time_offset_lidar_to_imu as a run would use them on a pcap or PCD folder).
LogSummary summarizeLog(const std::string& path, const InputConfig& input,
                        const SensorConfig& sensor, const ProgressFn& progress = {});

}  // namespace storey
