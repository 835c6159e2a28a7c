#pragma once
/// Puts scans and IMU samples, read in a log's record order, into time order:
/// checks each stream's stamps, drops what cannot be used (counted by reason)
/// and merges the two streams through a small bounded reorder buffer.
///
/// Within a stream, a message older than the stream's newest is put back in
/// order when it is newer than what was released and not a repeat (counted
/// in LogReadStats::reordered); a repeat is dropped as a duplicate, an older
/// one as backwards.
///
/// Order key: IMU samples by their stamp, scans by stamp + lidar-to-IMU time
/// offset (the scan keeps its own stamp); at equal keys IMU samples come first.
/// A message is released once a message keyed `window` later has been pushed,
/// when the buffer is full, or at the end of the input.
///
/// Clock jumps: once a stream's nominal period is known (the median of its
/// first 20 intervals), a message whose stamp is more than kClockJumpNs off
/// the next expected one (the stream's previous stamp + one period) while its
/// lead over the other stream's newest stamp changed by about as much (within
/// kClockJumpNs / 2: in a gap of one stream the other goes on, so the lead
/// stays) is held with the messages of its stream after it until the other
/// stream's next message and its own next one. If the other did not step
/// too (it is within half the step + its period of its previous one: not a
/// pause of both) and the stream goes on from the new stamp (within
/// kClockJumpNs / 2 of one period: not one garbled stamp), its clock jumped: its stamps from there
/// on are moved by minus the step (the jump minus one period) and the jump is recorded in
/// LogReadStats::clock_jumps. Otherwise the held messages go on as they were.
/// A forward jump is only told from a gap where the log is in record order
/// (bags); where the streams are merged by stamp (PCD folder + IMU CSV) it
/// is a gap.
#include <cstddef>
#include <cstdint>
#include <optional>
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
  /// Smallest step of a stream's stamps taken for a clock jump [ns].
  static constexpr std::int64_t kClockJumpNs = 400'000'000;

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
  void finish();
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
  /// One stream's stamps: the newest accepted, the shift applied to the rest
  /// after a clock jump, its nominal period, its lead over the other stream.
  struct Stream {
    bool have = false;
    std::int64_t last_ns = 0;   ///< newest accepted stamp (shifted)
    std::int64_t shift_ns = 0;  ///< added to the stamps read
    std::vector<std::int64_t> intervals;
    std::int64_t period_ns = 0;  ///< 0 until known
    bool have_lead = false;
    double lead_ns = 0.0;  ///< last_ns - the other stream's last_ns then (double: see ns())
  };
  /// The clock-jump check, then accept().
  void route(LogMessage&& message);
  /// The order and window checks of one message (stamp shifted), then insert().
  void accept(LogMessage&& message);
  /// Ends the hold of a suspected jump: `jumped` moves the held stream's clock.
  void resolve(bool jumped);
  void acceptScan(Scan&& scan);
  void acceptImu(const ImuSample& imu);
  /// A message older than its stream's newest (stamp shifted, key = order
  /// key): a duplicate of one buffered or the newest is dropped, one older
  /// than what was released is dropped as backwards; true: insert it.
  bool acceptOlder(int kind, std::int64_t stamp_ns, std::int64_t key_ns);
  /// Whether a message of `kind` keyed key_ns waits in the buffer.
  bool buffered(int kind, std::int64_t key_ns) const;
  void noteStamp(int kind, std::int64_t stamp_ns);

  Options options_;
  LogReadStats& stats_;
  std::vector<Entry> heap_;  ///< min-heap on (key, kind, arrival)
  std::uint64_t arrivals_ = 0;
  std::int64_t newest_key_ns_ = 0;
  bool have_released_ = false;
  std::int64_t released_key_ns_ = 0;
  Stream streams_[2];  ///< 0 IMU, 1 scans
  struct Suspect {
    int kind = 0;              ///< the stream that seems to have jumped
    std::int64_t step_ns = 0;  ///< its stamp minus the expected one
    std::int64_t other_last_ns = 0;
    bool other_seen = false;     ///< the other stream's next message came
    bool other_went_on = false;  ///< ... without the step
  };
  std::optional<Suspect> suspect_;
  std::vector<LogMessage> held_;  ///< the suspect and its stream's messages after it
  bool finished_ = false;
};

}  // namespace storey
