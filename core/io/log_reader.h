#pragma once
/// Streaming interface of every log format: scans and IMU samples in time
/// order, read lazily (memory bounded by one message, not by the log).
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "io/input_config.h"
#include "types/imu_sample.h"
#include "types/scan.h"
#include "types/sensor.h"

namespace storey {

using LogMessage = std::variant<Scan, ImuSample>;

/// A step in one stream's stamps that the other stream did not make
/// (io/message_sequencer.h); the stream's later stamps are moved back by it.
struct ClockJump {
  bool imu = false;           ///< the IMU stream jumped (else the LiDAR's)
  std::int64_t stamp_ns = 0;  ///< the first message after it, re-aligned [ns]
  std::int64_t step_ns = 0;   ///< how far its stamps jumped [ns]
};

/// What a reader skipped or repaired, with the reason; shown in the run report.
struct LogReadStats {
  std::int64_t scans = 0;                       ///< scans delivered
  std::int64_t imu_samples = 0;                 ///< IMU samples delivered
  std::int64_t points = 0;                      ///< points delivered
  std::map<std::string, std::int64_t> dropped;  ///< reason -> count (points or messages)
  std::vector<ClockJump> clock_jumps;           ///< in the order found
  /// Messages older than their stream's newest, put back in time order
  /// (within the reorder window; older ones are dropped as backwards).
  std::int64_t reordered = 0;
  /// The newest stamp read so far (readers that order messages deliver
  /// them up to their reorder window later) [ns].
  std::int64_t newest_read_ns = 0;
};

class LogReader {
 public:
  virtual ~LogReader() = default;
  /// Next scan or IMU sample in time order (scans by their stamp); false at the end.
  /// Throws storey::Error on input that cannot be read, naming file and place.
  virtual bool next(LogMessage& message) = 0;
  virtual const LogReadStats& stats() const = 0;
  /// Human-readable name of the source, e.g. "bag file.bag (/velodyne_points, /imu/data)".
  virtual std::string describe() const = 0;
  /// Fraction of the log read so far in [0, 1] (by time), or -1 when unknown.
  virtual double progress() const { return -1.0; }
};

/// Opens a log by its content (ROS1 bag, Velodyne pcap, PCD folder;
/// io/log_format.h) with the input options and the sensor set-up. Throws
/// storey::Error when the file is missing, empty, not a supported format, or
/// lacks point clouds or IMU.
std::unique_ptr<LogReader> openLog(const std::string& path, const InputConfig& input,
                                   const SensorConfig& sensor);

}  // namespace storey
