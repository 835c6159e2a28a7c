#include "io/imu_guard.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/message_sequencer.h"
#include "io/point_cloud_to_scan.h"

namespace storey {
namespace {

constexpr std::size_t kScanIntervalsForPeriod = 20;
constexpr double kScanGapPeriods = 1.5;        // one scan missing is a gap of two periods
constexpr std::size_t kSaturatedRun = 3;       // samples stuck at one value
constexpr float kOcclusionNear = 0.5f;         // points nearer do not count [m]
constexpr std::size_t kOcclusionHistory = 50;  // scans in the usual count's median
constexpr std::size_t kOcclusionMinHistory = 10;
constexpr std::int64_t kOcclusionMinUsual = 100;  // fewer usual points: no check
constexpr std::int64_t kOcclusionRelearnNs = 5'000'000'000;
constexpr double kOcclusionSkipFraction = 0.1;             // less of the usual left: skip the scan
constexpr std::int64_t kDropEpisodeGapNs = 1'000'000'000;  // a quiet second ends an episode

/// Channel c of a sample: gyro x y z (0-2), accel x y z (3-5).
double channel(const ImuSample& s, int c) {
  return c < 3 ? s.gyro[c] : s.accel[c - 3];
}

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
      saturation_gyro_(input.imu_saturation_gyro),
      saturation_accel_(input.imu_saturation_accel),
      occlusion_fraction_(input.lidar_occlusion_fraction),
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
      reportClockJumps();
      reportReaderDrops(0, true);
      endRun(nullptr);
      if (occlusion_) endOcclusion(occlusion_->last_ns + scan_period_ns_);
      release();  // the last sample has no right neighbour: it stays as it is
      break;
    }
    if (!first_ns_) first_ns_ = stampOf(in);
    reportClockJumps();
    // The time of the reader's drops: the newest stamp it read (it delivers
    // up to its reorder window later).
    reportReaderDrops(std::max(stampOf(in), inner_->stats().newest_read_ns), false);
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
  if (!checkOcclusion(scan)) return;  // too little left to register
  if (run_samples_ > 0) {
    run_.emplace_back(std::move(scan));
  } else {
    queueScan(std::move(scan));
  }
}

void GuardedLogReader::queueScan(Scan&& scan) {
  if (held_) {
    after_held_.push_back(std::move(scan));
  } else {
    ready_.emplace_back(std::move(scan));
  }
}

bool GuardedLogReader::checkOcclusion(Scan& scan) {
  if (occlusion_fraction_ <= 0.0) return true;
  std::int64_t far = 0;
  for (const ScanPoint& p : scan.points)
    if (p.p.squaredNorm() > kOcclusionNear * kOcclusionNear) ++far;
  if (occlusion_ && scan.stamp_ns - occlusion_->first_ns > kOcclusionRelearnNs) {
    // Occluded for too long to be a passer-by: a new scene; learn its count.
    endOcclusion(scan.stamp_ns);
    far_counts_.clear();
  }
  if (far_counts_.size() >= kOcclusionMinHistory) {
    std::vector<std::int64_t> counts(far_counts_.begin(), far_counts_.end());
    auto mid = counts.begin() + static_cast<std::ptrdiff_t>(counts.size() / 2);
    std::nth_element(counts.begin(), mid, counts.end());
    const std::int64_t usual = *mid;
    if (usual >= kOcclusionMinUsual &&
        static_cast<double>(far) < occlusion_fraction_ * static_cast<double>(usual)) {
      if (!occlusion_) occlusion_ = Occlusion{scan.stamp_ns, scan.stamp_ns, 0, 0, 0.0};
      occlusion_->last_ns = scan.stamp_ns;
      ++occlusion_->scans;
      const double fraction = static_cast<double>(far) / static_cast<double>(usual);
      occlusion_->fraction_sum += fraction;
      if (fraction < kOcclusionSkipFraction) {
        ++occlusion_->skipped;
        return false;
      }
      // What is in front of the sensor goes; what lies beyond it is registered.
      scan.points.erase(std::remove_if(scan.points.begin(), scan.points.end(),
                                       [](const ScanPoint& p) {
                                         return p.p.squaredNorm() <=
                                                kOcclusionNear * kOcclusionNear;
                                       }),
                        scan.points.end());
      return true;
    }
  }
  if (occlusion_) endOcclusion(scan.stamp_ns);
  far_counts_.push_back(far);  // only clear scans make the usual count
  if (far_counts_.size() > kOcclusionHistory) far_counts_.pop_front();
  return true;
}

void GuardedLogReader::endOcclusion(std::int64_t end_ns) {
  const Occlusion o = *occlusion_;
  occlusion_.reset();
  const double duration = nsToSeconds(end_ns - o.first_ns);
  faults_.add(kFaultLidarOccluded,
              {sinceStart(o.first_ns), duration,
               std::to_string(o.scans) + (o.scans == 1 ? " scan" : " scans") + " with " +
                   fixed(100.0 * o.fraction_sum / static_cast<double>(o.scans), 0) +
                   " % of the usual points beyond 0.5 m, " + fixed(duration, 2) + " s, " +
                   std::to_string(o.skipped) + " skipped"},
              "LiDAR occluded",
              "the points within 0.5 m of the sensor are removed from those scans and the rest "
              "registered; a scan with less than 10 % of the usual points left is skipped (the "
              "IMU carries the motion across it)");
}

void GuardedLogReader::reportClockJumps() {
  const std::vector<ClockJump>& jumps = inner_->stats().clock_jumps;
  for (; clock_jumps_reported_ < jumps.size(); ++clock_jumps_reported_) {
    const ClockJump& j = jumps[clock_jumps_reported_];
    const double step = nsToSeconds(j.step_ns);
    faults_.add(kFaultClockJump,
                {sinceStart(j.stamp_ns), 0.0,
                 std::string(j.imu ? "IMU" : "LiDAR") + " stamps jumped by " +
                     (step >= 0.0 ? "+" : "") + fixed(step, 3) + " s"},
                "clock jump",
                std::string("the ") + (j.imu ? "IMU" : "LiDAR") +
                    " stamps after it are moved back onto the other stream's clock by the step");
  }
}

void GuardedLogReader::reportReaderDrops(std::int64_t now_ns, bool at_end) {
  const LogReadStats& stats = inner_->stats();
  const auto fresh = [&](const char* reason) {
    const auto it = stats.dropped.find(reason);
    const std::int64_t count = it == stats.dropped.end() ? 0 : it->second;
    std::int64_t& seen = drops_seen_[reason];
    const std::int64_t added = count - seen;
    seen = count;
    return added;
  };
  const auto note = [&](const std::string& kind, std::int64_t imu, std::int64_t scans,
                        std::int64_t points, std::int64_t reordered) {
    if (imu + scans + points + reordered == 0) return;
    auto it = drop_episodes_.find(kind);
    if (it == drop_episodes_.end()) {
      it = drop_episodes_.emplace(kind, DropEpisode{now_ns, now_ns, 0, 0, 0, 0}).first;
    }
    DropEpisode& e = it->second;
    e.last_ns = now_ns;
    e.imu += imu;
    e.scans += scans;
    e.points += points;
    e.reordered += reordered;
  };
  // Episodes quiet for a second end before new counts start the next one.
  for (auto it = drop_episodes_.begin(); it != drop_episodes_.end();) {
    const std::string kind = it->first;
    ++it;
    if (at_end || now_ns - drop_episodes_.at(kind).last_ns > kDropEpisodeGapNs)
      endDropEpisode(kind);
  }
  if (at_end) return;
  note(kFaultDuplicates, fresh(kDropImuDuplicate), fresh(kDropScanDuplicate), 0, 0);
  const std::int64_t reordered = stats.reordered - reordered_seen_;
  reordered_seen_ = stats.reordered;
  note(kFaultOutOfOrder, fresh(kDropImuBackwards) + fresh(kDropImuLate),
       fresh(kDropScanBackwards) + fresh(kDropScanLate), 0, reordered);
  note(kFaultNotFinite, fresh(kDropImuNotFinite), 0, fresh(kDropPointNotFinite), 0);
}

void GuardedLogReader::endDropEpisode(const std::string& kind) {
  const DropEpisode e = drop_episodes_.at(kind);
  drop_episodes_.erase(kind);
  const double duration = nsToSeconds(e.last_ns - e.first_ns);
  const auto count = [](std::int64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  std::string what, detail, handling;
  if (kind == kFaultDuplicates) {
    what = "repeated messages";
    detail = count(e.imu, "IMU sample", "IMU samples") + " and " + count(e.scans, "scan", "scans") +
             " recorded twice";
    handling = "the repeats are dropped";
  } else if (kind == kFaultOutOfOrder) {
    what = "messages out of order";
    detail = count(e.reordered, "message", "messages") + " put back in order, " +
             count(e.imu, "IMU sample", "IMU samples") + " and " + count(e.scans, "scan", "scans") +
             " too late for the reorder window";
    handling =
        "messages recorded late are put back in time order within the 1 s reorder "
        "window; later ones are dropped";
  } else {
    what = "NaN or infinite values";
    detail =
        count(e.imu, "IMU sample", "IMU samples") + " and " + count(e.points, "point", "points");
    handling = "dropped (an IMU sample missing is bridged like any dropout)";
  }
  faults_.add(kind, {sinceStart(e.first_ns), duration, detail}, what, handling);
}

void GuardedLogReader::onImu(const ImuSample& sample) {
  const auto stuck = [&](int c, double value) {
    const double limit = c < 3 ? saturation_gyro_ : saturation_accel_;
    return limit > 0.0 && std::abs(value) >= limit;
  };
  if (run_samples_ > 0) {
    const ImuSample& last =
        std::get<ImuSample>(*std::find_if(run_.rbegin(), run_.rend(), [](const LogMessage& m) {
          return !std::holds_alternative<Scan>(m);
        }));
    unsigned still = 0;
    for (int c = 0; c < 6; ++c)
      if ((run_channels_ >> c & 1u) && channel(sample, c) == channel(last, c)) still |= 1u << c;
    if (still != 0) {
      run_channels_ = still;
      run_.emplace_back(sample);
      ++run_samples_;
      return;
    }
    endRun(&sample);
  }
  unsigned extreme = 0;
  for (int c = 0; c < 6; ++c)
    if (stuck(c, channel(sample, c))) extreme |= 1u << c;
  if (extreme != 0) {
    run_channels_ = extreme;
    run_.emplace_back(sample);
    run_samples_ = 1;
    return;
  }
  judgeImu(sample);
}

void GuardedLogReader::endRun(const ImuSample* next) {
  if (run_samples_ == 0) return;
  std::deque<LogMessage> run;
  run.swap(run_);
  const std::size_t samples = run_samples_;
  run_samples_ = 0;
  if (samples < kSaturatedRun) {
    // Not saturation: the samples go on to the other checks.
    for (LogMessage& m : run) {
      if (auto* scan = std::get_if<Scan>(&m)) {
        queueScan(std::move(*scan));
      } else {
        judgeImu(std::get<ImuSample>(m));
      }
    }
    return;
  }
  const ImuSample* first = nullptr;
  const ImuSample* last = nullptr;
  for (const LogMessage& m : run) {
    if (const auto* s = std::get_if<ImuSample>(&m)) {
      if (!first) first = s;
      last = s;
    }
  }
  int axis = 0;
  while (!(run_channels_ >> axis & 1u)) ++axis;
  const std::int64_t end_ns = next ? next->stamp_ns : last->stamp_ns;
  const double duration = nsToSeconds(end_ns - first->stamp_ns);
  static const char* const kAxes[6] = {"gyro x",  "gyro y",  "gyro z",
                                       "accel x", "accel y", "accel z"};
  faults_.add(kFaultImuSaturation,
              {sinceStart(first->stamp_ns), duration,
               std::to_string(samples) + " samples stuck at " + kAxes[axis] + " " +
                   fixed(channel(*first, axis), 1) + (axis < 3 ? " rad/s" : " m/s^2") + ", " +
                   fixed(duration, 3) + " s"},
              "IMU saturation",
              "the samples are removed and the IMU factor across them gets the uncertainty of "
              "unknown motion");
  after_removed_ = true;
  for (LogMessage& m : run)
    if (auto* scan = std::get_if<Scan>(&m)) queueScan(std::move(*scan));
}

void GuardedLogReader::judgeImu(const ImuSample& in) {
  ImuSample sample = in;
  if (after_removed_) {
    sample.after_removed = true;
    after_removed_ = false;
  }
  const ImuSample* newest = held_ ? &*held_ : before_ ? &*before_ : nullptr;
  if (newest && sample.stamp_ns - newest->stamp_ns > gap_ns_ && !sample.after_removed) {
    const double gap = nsToSeconds(sample.stamp_ns - newest->stamp_ns);
    faults_.add(kFaultImuGap,
                {sinceStart(newest->stamp_ns), gap, fixed(gap, 3) + " s without IMU samples"},
                "IMU gap",
                "its motion is left to the LiDAR (the IMU factor across it is given the "
                "uncertainty of unknown motion)");
  }
  if (held_ && before_ && sample.stamp_ns - before_->stamp_ns <= gap_ns_ && !sample.after_removed &&
      !held_->after_removed) {
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
