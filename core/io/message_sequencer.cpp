#include "io/message_sequencer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace storey {
namespace {

struct Later {
  template <typename E>
  bool operator()(const E& a, const E& b) const {
    if (a.key_ns != b.key_ns) return a.key_ns > b.key_ns;
    if (a.kind != b.kind) return a.kind > b.kind;
    return a.arrival > b.arrival;
  }
};

constexpr std::size_t kIntervalsForPeriod = 20;
constexpr std::size_t kMaxHeld = 8192;

int kindOf(const LogMessage& m) {
  return std::holds_alternative<Scan>(m) ? 1 : 0;
}

std::int64_t& stampOf(LogMessage& m) {
  if (auto* scan = std::get_if<Scan>(&m)) return scan->stamp_ns;
  return std::get<ImuSample>(m).stamp_ns;
}

// Differences of stamps for the jump checks, in double: a log's stamps can
// lie anywhere in +-2^62 ns (ROS 1 seconds are unsigned 32-bit), so sums of
// three of them overflow int64; the checks only need about a microsecond.
double ns(std::int64_t v) {
  return static_cast<double>(v);
}

// A larger step is no clock jump but a stamp outside every log format's
// range (2^32 s): it goes on to the order checks unchanged. A clock set from
// 1970 to today by a late time sync (1.7e18 ns) is a jump.
constexpr double kMaxClockJumpNs = 5e18;

// stamp + shift, false when it leaves int64 (then the message is dropped).
bool shifted(std::int64_t stamp_ns, std::int64_t shift_ns, std::int64_t& out) {
  return !__builtin_add_overflow(stamp_ns, shift_ns, &out);
}

}  // namespace

MessageSequencer::MessageSequencer(const Options& options, LogReadStats& stats)
    : options_(options), stats_(stats) {}

void MessageSequencer::push(Scan&& scan) {
  route(LogMessage(std::move(scan)));
}

void MessageSequencer::push(const ImuSample& imu) {
  stats_.newest_read_ns = std::max(stats_.newest_read_ns, imu.stamp_ns);
  if (!imu.isFinite()) {
    ++stats_.dropped[kDropImuNotFinite];
    return;
  }
  route(LogMessage(imu));
}

void MessageSequencer::finish() {
  if (suspect_) resolve(false);
  finished_ = true;
}

void MessageSequencer::route(LogMessage&& message) {
  const int kind = kindOf(message);
  stats_.newest_read_ns = std::max(stats_.newest_read_ns, stampOf(message));
  if (suspect_) {
    const bool held = kind == suspect_->kind;
    const std::int64_t period = streams_[suspect_->kind].period_ns;
    if (held) {
      held_.push_back(std::move(message));
    } else if (!suspect_->other_seen) {
      // The other stream's next message: did it step as well (a pause of both)?
      const Stream& other = streams_[kind];
      const double step = ns(stampOf(message)) + ns(other.shift_ns) - ns(suspect_->other_last_ns);
      suspect_->other_seen = true;
      suspect_->other_went_on =
          std::abs(step) < std::abs(ns(suspect_->step_ns)) / 2 + ns(other.period_ns);
    }
    if (suspect_->other_seen && held_.size() >= 2) {
      // And the stream goes on from the new stamp (not one garbled stamp)?
      const double next = ns(stampOf(held_[1])) - ns(stampOf(held_[0])) - ns(period);
      resolve(suspect_->other_went_on && std::abs(next) < ns(kClockJumpNs) / 2);
    } else if (held_.size() > kMaxHeld) {
      resolve(false);
    }
    if (held) return;
    accept(std::move(message));  // one check at a time
    return;
  }
  const Stream& own = streams_[kind];
  const Stream& other = streams_[1 - kind];
  if (own.have && own.period_ns > 0 && own.have_lead && other.have) {
    const double stamp = ns(stampOf(message)) + ns(own.shift_ns);
    const double step = stamp - ns(own.last_ns) - ns(own.period_ns);
    const double lead_change = (stamp - ns(other.last_ns)) - own.lead_ns;
    if (std::abs(step) > ns(kClockJumpNs) && std::abs(step) < kMaxClockJumpNs &&
        std::abs(lead_change - step) < ns(kClockJumpNs) / 2) {
      // The step exactly (the double above is within a microsecond of it).
      std::int64_t stamp_ns = 0, step_ns = 0;
      if (shifted(stampOf(message), own.shift_ns, stamp_ns) &&
          !__builtin_sub_overflow(stamp_ns, own.last_ns, &step_ns) &&
          !__builtin_sub_overflow(step_ns, own.period_ns, &step_ns)) {
        suspect_ = Suspect{kind, step_ns, other.last_ns, false, false};
        held_.push_back(std::move(message));
        return;
      }
    }
  }
  accept(std::move(message));
}

void MessageSequencer::resolve(bool jumped) {
  const Suspect suspect = *suspect_;
  suspect_.reset();
  std::vector<LogMessage> held;
  held.swap(held_);
  Stream& stream = streams_[suspect.kind];
  std::int64_t shift_ns = 0;
  if (jumped && !__builtin_sub_overflow(stream.shift_ns, suspect.step_ns, &shift_ns)) {
    stream.shift_ns = shift_ns;
    std::int64_t at_ns = stampOf(held.front());
    if (!shifted(at_ns, stream.shift_ns, at_ns)) at_ns = stampOf(held.front());
    stats_.clock_jumps.push_back(ClockJump{suspect.kind == 0, at_ns, suspect.step_ns});
  }
  for (LogMessage& m : held) accept(std::move(m));
}

void MessageSequencer::accept(LogMessage&& message) {
  if (auto* scan = std::get_if<Scan>(&message)) {
    acceptScan(std::move(*scan));
  } else {
    acceptImu(std::get<ImuSample>(message));
  }
}

void MessageSequencer::noteStamp(int kind, std::int64_t stamp_ns) {
  Stream& stream = streams_[kind];
  const Stream& other = streams_[1 - kind];
  if (stream.have && stream.period_ns == 0) {
    std::int64_t interval_ns = 0;
    if (!__builtin_sub_overflow(stamp_ns, stream.last_ns, &interval_ns))
      stream.intervals.push_back(interval_ns);
    if (stream.intervals.size() == kIntervalsForPeriod) {
      auto mid = stream.intervals.begin() + kIntervalsForPeriod / 2;
      std::nth_element(stream.intervals.begin(), mid, stream.intervals.end());
      stream.period_ns = *mid;
      stream.intervals.clear();
    }
  }
  stream.have = true;
  stream.last_ns = stamp_ns;
  stream.have_lead = other.have;
  stream.lead_ns = ns(stamp_ns) - ns(other.last_ns);
}

bool MessageSequencer::buffered(int kind, std::int64_t key_ns) const {
  return std::any_of(heap_.begin(), heap_.end(),
                     [&](const Entry& e) { return e.kind == kind && e.key_ns == key_ns; });
}

bool MessageSequencer::acceptOlder(int kind, std::int64_t stamp_ns, std::int64_t key_ns) {
  const Stream& stream = streams_[kind];
  if (stamp_ns == stream.last_ns || buffered(kind, key_ns)) {
    ++stats_.dropped[kind == 0 ? kDropImuDuplicate : kDropScanDuplicate];
    return false;
  }
  if (have_released_ && key_ns <= released_key_ns_) {  // too late to be put in place
    ++stats_.dropped[kind == 0 ? kDropImuBackwards : kDropScanBackwards];
    return false;
  }
  ++stats_.reordered;
  return true;
}

void MessageSequencer::acceptScan(Scan&& scan) {
  Stream& stream = streams_[1];
  std::int64_t key = 0;
  if (!shifted(scan.stamp_ns, stream.shift_ns, scan.stamp_ns) ||
      !shifted(scan.stamp_ns, options_.lidar_to_imu_offset_ns, key)) {
    ++stats_.dropped[kDropScanBackwards];
    return;
  }
  if (stream.have && scan.stamp_ns <= stream.last_ns) {
    // Older than the stream's newest: a repeat, or recorded out of order.
    if (acceptOlder(1, scan.stamp_ns, key)) insert(key, 1, LogMessage(std::move(scan)));
    return;
  }
  noteStamp(1, scan.stamp_ns);
  if (have_released_ && key < released_key_ns_) {
    ++stats_.dropped[kDropScanLate];
    return;
  }
  insert(key, 1, LogMessage(std::move(scan)));
}

void MessageSequencer::acceptImu(const ImuSample& in) {
  Stream& stream = streams_[0];
  ImuSample imu = in;
  if (!shifted(imu.stamp_ns, stream.shift_ns, imu.stamp_ns)) {
    ++stats_.dropped[kDropImuBackwards];
    return;
  }
  if (stream.have && imu.stamp_ns <= stream.last_ns) {
    if (acceptOlder(0, imu.stamp_ns, imu.stamp_ns)) insert(imu.stamp_ns, 0, LogMessage(imu));
    return;
  }
  noteStamp(0, imu.stamp_ns);
  if (have_released_ && imu.stamp_ns < released_key_ns_) {
    ++stats_.dropped[kDropImuLate];
    return;
  }
  insert(imu.stamp_ns, 0, LogMessage(imu));
}

void MessageSequencer::insert(std::int64_t key_ns, int kind, LogMessage&& message) {
  newest_key_ns_ = heap_.empty() && !have_released_ ? key_ns : std::max(newest_key_ns_, key_ns);
  heap_.push_back(Entry{key_ns, kind, arrivals_++, std::move(message)});
  std::push_heap(heap_.begin(), heap_.end(), Later());
}

bool MessageSequencer::pop(LogMessage& message) {
  if (heap_.empty()) return false;
  const Entry& oldest = heap_.front();
  const bool ready = finished_ || heap_.size() > options_.max_buffered ||
                     newest_key_ns_ - oldest.key_ns >= options_.window_ns;
  if (!ready) return false;
  std::pop_heap(heap_.begin(), heap_.end(), Later());
  Entry entry = std::move(heap_.back());
  heap_.pop_back();
  have_released_ = true;
  released_key_ns_ = entry.key_ns;
  if (const auto* scan = std::get_if<Scan>(&entry.message)) {
    ++stats_.scans;
    stats_.points += static_cast<std::int64_t>(scan->points.size());
  } else {
    ++stats_.imu_samples;
  }
  message = std::move(entry.message);
  return true;
}

}  // namespace storey
