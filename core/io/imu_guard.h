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
/// - a LiDAR gap: consecutive scans further apart than 2.5 scan periods
///   (the median of the first 20 intervals).
/// Each becomes a FaultLog event; messages pass on in the same order.
#include <deque>
#include <memory>
#include <optional>
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
  void onImu(const ImuSample& sample);
  void onScan(Scan&& scan);
  /// Moves the held sample and the messages after it to the output.
  void release();
  double sinceStart(std::int64_t stamp_ns) const;

  std::unique_ptr<LogReader> inner_;
  double spike_gyro_, spike_accel_;
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
};

}  // namespace storey
