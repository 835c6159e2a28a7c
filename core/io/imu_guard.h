#pragma once
/// A log reader that checks the IMU and scan streams of another one as they
/// pass (docs/faults.md), holding back one IMU sample (and the scans after
/// it) to see both neighbours of each sample:
/// - a spike: a sample whose angular rate (specific force) differs from its
///   neighbours' mean by more than input.imu_spike_gyro (imu_spike_accel)
///   while the neighbours agree within half of that, all three within the
///   IMU gap threshold: a saturated or garbled reading. It is replaced by the
///   neighbours' linear interpolation at its stamp.
/// - an IMU gap: consecutive samples further apart than imuGapThreshold()
///   (the odometry then lets the LiDAR carry the motion across it).
/// - a LiDAR gap: consecutive scans further apart than 1.5 scan periods
///   (the median of the first 20 intervals).
/// - IMU saturation: three or more consecutive samples holding the same value
///   on one axis, at least input.imu_saturation_gyro (imu_saturation_accel)
///   from zero (the sensor clipped at its range). The run is removed and the
///   sample after it marked ImuSample::after_removed: the IMU factor across
///   it gets the uncertainty of unknown motion, as across a dropout.
/// - LiDAR occlusion: a scan with fewer points beyond 0.5 m than
///   input.lidar_occlusion_fraction of the median of the last 50 scans that
///   were not occluded (a person in front of the sensor). Its points within
///   0.5 m (the body) are removed, so they neither enter the map nor pull
///   the registration; with less than 10 % of the usual points left the scan
///   is not passed on at all (the IMU carries the motion across it).
///   Consecutive ones are one event. After 5 s of occlusion the usual count
///   is learnt again, so a lasting change of scene is not an occlusion.
/// - a clock jump found by the reader's sequencer (LogReadStats::clock_jumps,
///   io/message_sequencer.h), reported as it appears.
/// Each becomes a FaultLog event; messages pass on in the same order.
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/fault_log.h"
#include "io/input_config.h"
#include "io/log_reader.h"
#include "types/sensor.h"

namespace storey {

class GuardedLogReader : public LogReader {
 public:
  /// `faults` must outlive the reader.
  GuardedLogReader(std::unique_ptr<LogReader> inner, const InputConfig& input, const ImuNoise& imu,
                   FaultLog& faults);

  bool next(LogMessage& message) override;
  const LogReadStats& stats() const override { return inner_->stats(); }
  std::string describe() const override { return inner_->describe(); }
  double progress() const override { return inner_->progress(); }

 private:
  /// The saturation check: holds a possible saturated run (and the scans
  /// read meanwhile) until it ends, then removes it or passes it on.
  void onImu(const ImuSample& sample);
  /// The spike and gap checks of one sample.
  void judgeImu(const ImuSample& sample);
  /// Ends the candidate run before `next` (nullptr: the end of the log).
  void endRun(const ImuSample* next);
  void onScan(Scan&& scan);
  /// The occlusion check: removes the near points of an occluded scan;
  /// false: too little is left, the scan is skipped.
  bool checkOcclusion(Scan& scan);
  void endOcclusion(std::int64_t end_ns);
  /// Queues a scan behind the samples held back.
  void queueScan(Scan&& scan);
  void reportClockJumps();
  /// The reader's drops and repairs since the last call as fault episodes:
  /// repeats, messages out of order, non-finite values; an episode ends
  /// after a second without one (`now_ns`: the newest stamp read; at_end:
  /// every episode ends).
  void reportReaderDrops(std::int64_t now_ns, bool at_end);
  /// Moves the held sample and the messages after it to the output.
  void release();
  double sinceStart(std::int64_t stamp_ns) const;

  std::unique_ptr<LogReader> inner_;
  double spike_gyro_, spike_accel_;
  double saturation_gyro_, saturation_accel_, occlusion_fraction_;
  std::int64_t gap_ns_;
  FaultLog& faults_;
  bool ended_ = false;
  std::optional<std::int64_t> first_ns_;
  std::deque<LogMessage> ready_;
  std::optional<ImuSample> before_;  ///< the last sample released
  std::optional<ImuSample> held_;    ///< the newest sample, not yet judged
  std::deque<Scan> after_held_;      ///< scans read after the held sample
  std::optional<std::int64_t> last_scan_ns_;
  std::vector<std::int64_t> scan_intervals_ns_;  ///< the first ones, for the period
  std::int64_t scan_period_ns_ = 0;              ///< 0 until known
  // Saturation: the candidate run (samples and the scans read meanwhile).
  std::deque<LogMessage> run_;
  std::size_t run_samples_ = 0;
  unsigned run_channels_ = 0;   ///< bit c: channel c (gyro x y z, accel x y z) stuck
  bool after_removed_ = false;  ///< the next sample follows a removed run
  // Occlusion: points beyond 0.5 m of the last clear scans; the open event.
  std::deque<std::int64_t> far_counts_;
  struct Occlusion {
    std::int64_t first_ns = 0, last_ns = 0;
    std::int64_t scans = 0;
    std::int64_t skipped = 0;   ///< with too little left to register
    double fraction_sum = 0.0;  ///< of the scans' far points over the median
  };
  std::optional<Occlusion> occlusion_;
  std::size_t clock_jumps_reported_ = 0;
  // Reader drops: the counts seen so far, the open episode of each kind.
  struct DropEpisode {
    std::int64_t first_ns = 0, last_ns = 0;
    std::int64_t imu = 0, scans = 0, points = 0, reordered = 0;
  };
  std::map<std::string, std::int64_t> drops_seen_;
  std::int64_t reordered_seen_ = 0;
  std::map<std::string, DropEpisode> drop_episodes_;  ///< by fault kind
  void endDropEpisode(const std::string& kind);
};

}  // namespace storey
