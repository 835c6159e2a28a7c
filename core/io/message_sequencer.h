#pragma once
/// Puts scans and IMU samples, read in a log's record order, into time order:
/// checks each stream's stamps, drops what cannot be used (counted by reason)
/// and merges the two streams through a small bounded reorder buffer.
///
/// Order key: IMU samples by their stamp, scans by stamp + lidar-to-IMU time
/// offset (the scan keeps its own stamp); at equal keys IMU samples come first.
/// A message is released once a message keyed `window` later has been pushed,
/// when the buffer is full, or at the end of the input.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "io/log_reader.h"

namespace storey {

/// Keys of LogReadStats::dropped for messages (counts of messages).
inline constexpr const char* kDropImuNotFinite = "imu_not_finite";
inline constexpr const char* kDropImuMissingData = "imu_missing_gyro_or_accel";
inline constexpr const char* kDropImuBackwards = "imu_stamp_backwards";
inline constexpr const char* kDropImuDuplicate = "imu_stamp_duplicate";
inline constexpr const char* kDropScanBackwards = "scan_stamp_backwards";
inline constexpr const char* kDropScanDuplicate = "scan_stamp_duplicate";
inline constexpr const char* kDropImuLate = "imu_later_than_reorder_window";
inline constexpr const char* kDropScanLate = "scan_later_than_reorder_window";

class MessageSequencer {
 public:
  struct Options {
    std::int64_t lidar_to_imu_offset_ns = 0;  ///< t_imu = t_lidar + offset [ns]
    std::int64_t window_ns = 1'000'000'000;   ///< reorder window [ns]
    std::size_t max_buffered = 4096;          ///< messages held at most
  };

  /// Counts deliveries and drops into `stats`, which must outlive the sequencer.
  MessageSequencer(const Options& options, LogReadStats& stats);

  void push(Scan&& scan);
  void push(const ImuSample& imu);
  /// No more input: everything buffered becomes ready.
  void finish() { finished_ = true; }
  /// Takes the next message in time order if one is ready.
  bool pop(LogMessage& message);

  std::size_t buffered() const { return heap_.size(); }

 private:
  struct Entry {
    std::int64_t key_ns;
    int kind;  ///< 0 IMU, 1 scan: IMU first at equal keys
    std::uint64_t arrival;
    LogMessage message;
  };
  void insert(std::int64_t key_ns, int kind, LogMessage&& message);

  Options options_;
  LogReadStats& stats_;
  std::vector<Entry> heap_;  ///< min-heap on (key, kind, arrival)
  std::uint64_t arrivals_ = 0;
  std::int64_t newest_key_ns_ = 0;
  bool have_released_ = false;
  std::int64_t released_key_ns_ = 0;
  bool have_imu_ = false;
  std::int64_t last_imu_ns_ = 0;
  bool have_scan_ = false;
  std::int64_t last_scan_ns_ = 0;
  bool finished_ = false;
};

}  // namespace storey
