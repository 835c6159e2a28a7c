#include "io/imu_guard.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace storey {
namespace {

constexpr std::size_t kScanIntervalsForPeriod = 20;
constexpr double kScanGapPeriods = 2.5;

std::int64_t stampOf(const LogMessage& m) {
  return std::holds_alternative<Scan>(m) ? std::get<Scan>(m).stamp_ns
                                         : std::get<ImuSample>(m).stamp_ns;
}

std::string fixed(double value, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << value;
  return os.str();
}

}  // namespace

GuardedLogReader::GuardedLogReader(std::unique_ptr<LogReader> inner, const InputConfig& input,
                                   const ImuNoise& imu, FaultLog& faults)
    : inner_(std::move(inner)),
      spike_gyro_(input.imu_spike_gyro),
      spike_accel_(input.imu_spike_accel),
      gap_ns_(secondsToNs(imuGapThreshold(imu))),
      faults_(faults) {}

double GuardedLogReader::sinceStart(std::int64_t stamp_ns) const {
  return nsToSeconds(stamp_ns - first_ns_.value_or(stamp_ns));
}

bool GuardedLogReader::next(LogMessage& message) {
  while (ready_.empty() && !ended_) {
    LogMessage in;
    if (!inner_->next(in)) {
      ended_ = true;
      release();  // the last sample has no right neighbour: it stays as it is
      break;
    }
    if (!first_ns_) first_ns_ = stampOf(in);
    if (auto* scan = std::get_if<Scan>(&in)) {
      onScan(std::move(*scan));
    } else {
      onImu(std::get<ImuSample>(in));
    }
  }
  if (ready_.empty()) return false;
  message = std::move(ready_.front());
  ready_.pop_front();
  return true;
}

void GuardedLogReader::onScan(Scan&& scan) {
  if (last_scan_ns_) {
    const std::int64_t dt = scan.stamp_ns - *last_scan_ns_;
    if (scan_period_ns_ == 0) {
      if (dt > 0) scan_intervals_ns_.push_back(dt);
      if (scan_intervals_ns_.size() == kScanIntervalsForPeriod) {
        auto mid = scan_intervals_ns_.begin() + kScanIntervalsForPeriod / 2;
        std::nth_element(scan_intervals_ns_.begin(), mid, scan_intervals_ns_.end());
        scan_period_ns_ = *mid;
      }
    } else if (dt > kScanGapPeriods * scan_period_ns_) {
      const double missing = nsToSeconds(dt - scan_period_ns_);
      const auto scans =
          static_cast<long>(std::lround(static_cast<double>(dt) / scan_period_ns_)) - 1;
      faults_.add(kFaultLidarGap,
                  {sinceStart(*last_scan_ns_), missing,
                   std::to_string(scans) + " scans missing, " + fixed(missing, 2) + " s"},
                  "LiDAR gap",
                  "the IMU alone carries the motion across it, then the scans are registered "
                  "again");
    }
  }
  last_scan_ns_ = scan.stamp_ns;
  if (held_) {
    after_held_.push_back(std::move(scan));
  } else {
    ready_.emplace_back(std::move(scan));
  }
}

void GuardedLogReader::onImu(const ImuSample& sample) {
  const ImuSample* newest = held_ ? &*held_ : before_ ? &*before_ : nullptr;
  if (newest && sample.stamp_ns - newest->stamp_ns > gap_ns_) {
    const double gap = nsToSeconds(sample.stamp_ns - newest->stamp_ns);
    faults_.add(kFaultImuGap,
                {sinceStart(newest->stamp_ns), gap, fixed(gap, 3) + " s without IMU samples"},
                "IMU gap",
                "its motion is left to the LiDAR (the IMU factor across it is given the "
                "uncertainty of unknown motion)");
  }
  if (held_ && before_ && sample.stamp_ns - before_->stamp_ns <= gap_ns_) {
    // Judge the held sample b between a = before_ and c = sample.
    ImuSample& b = *held_;
    const ImuSample& a = *before_;
    const double f = static_cast<double>(b.stamp_ns - a.stamp_ns) /
                     static_cast<double>(sample.stamp_ns - a.stamp_ns);
    const Eigen::Vector3d gyro = a.gyro + f * (sample.gyro - a.gyro);
    const Eigen::Vector3d accel = a.accel + f * (sample.accel - a.accel);
    const double dg = (b.gyro - gyro).norm(), da = (b.accel - accel).norm();
    const bool gyro_spike =
        spike_gyro_ > 0.0 && dg > spike_gyro_ && (sample.gyro - a.gyro).norm() < spike_gyro_ / 2;
    const bool accel_spike = spike_accel_ > 0.0 && da > spike_accel_ &&
                             (sample.accel - a.accel).norm() < spike_accel_ / 2;
    if (gyro_spike || accel_spike) {
      faults_.add(kFaultImuSpike,
                  {sinceStart(b.stamp_ns), 0.0,
                   "rate " + fixed(dg, 1) + " rad/s and force " + fixed(da, 1) +
                       " m/s^2 off its neighbours"},
                  "IMU spike", "the sample is replaced by its neighbours' interpolation");
      b.gyro = gyro;
      b.accel = accel;
    }
  }
  release();
  held_ = sample;
}

void GuardedLogReader::release() {
  if (held_) {
    ready_.emplace_back(*held_);
    before_ = held_;
    held_.reset();
  }
  while (!after_held_.empty()) {
    ready_.emplace_back(std::move(after_held_.front()));
    after_held_.pop_front();
  }
}

}  // namespace storey
