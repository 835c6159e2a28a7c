#include "io/message_sequencer.h"

#include <algorithm>
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

}  // namespace

MessageSequencer::MessageSequencer(const Options& options, LogReadStats& stats)
    : options_(options), stats_(stats) {}

void MessageSequencer::push(Scan&& scan) {
  route(LogMessage(std::move(scan)));
}

void MessageSequencer::push(const ImuSample& imu) {
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
  if (suspect_) {
    const bool held = kind == suspect_->kind;
    const std::int64_t period = streams_[suspect_->kind].period_ns;
    if (held) {
      held_.push_back(std::move(message));
    } else if (!suspect_->other_seen) {
      // The other stream's next message: did it step as well (a pause of both)?
      const Stream& other = streams_[kind];
      const std::int64_t step = stampOf(message) + other.shift_ns - suspect_->other_last_ns;
      suspect_->other_seen = true;
      suspect_->other_went_on = std::abs(step) < std::abs(suspect_->step_ns) / 2 + other.period_ns;
    }
    if (suspect_->other_seen && held_.size() >= 2) {
      // And the stream goes on from the new stamp (not one garbled stamp)?
      const std::int64_t next = stampOf(held_[1]) - stampOf(held_[0]) - period;
      resolve(suspect_->other_went_on && std::abs(next) < kClockJumpNs / 2);
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
    const std::int64_t stamp = stampOf(message) + own.shift_ns;
    const std::int64_t step = stamp - own.last_ns - own.period_ns;
    const std::int64_t lead_change = (stamp - other.last_ns) - own.lead_ns;
    if (std::abs(step) > kClockJumpNs && std::abs(lead_change - step) < kClockJumpNs / 2) {
      suspect_ = Suspect{kind, step, other.last_ns, false, false};
      held_.push_back(std::move(message));
      return;
    }
  }
  accept(std::move(message));
}

void MessageSequencer::resolve(bool jumped) {
  const Suspect suspect = *suspect_;
  suspect_.reset();
  std::vector<LogMessage> held;
  held.swap(held_);
  if (jumped) {
    Stream& stream = streams_[suspect.kind];
    stream.shift_ns -= suspect.step_ns;
    stats_.clock_jumps.push_back(
        ClockJump{suspect.kind == 0, stampOf(held.front()) + stream.shift_ns, suspect.step_ns});
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
    stream.intervals.push_back(stamp_ns - stream.last_ns);
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
  stream.lead_ns = stamp_ns - other.last_ns;
}

void MessageSequencer::acceptScan(Scan&& scan) {
  Stream& stream = streams_[1];
  scan.stamp_ns += stream.shift_ns;
  if (stream.have && scan.stamp_ns <= stream.last_ns) {
    ++stats_.dropped[scan.stamp_ns == stream.last_ns ? kDropScanDuplicate : kDropScanBackwards];
    return;
  }
  noteStamp(1, scan.stamp_ns);
  const std::int64_t key = scan.stamp_ns + options_.lidar_to_imu_offset_ns;
  if (have_released_ && key < released_key_ns_) {
    ++stats_.dropped[kDropScanLate];
    return;
  }
  insert(key, 1, LogMessage(std::move(scan)));
}

void MessageSequencer::acceptImu(const ImuSample& in) {
  Stream& stream = streams_[0];
  ImuSample imu = in;
  imu.stamp_ns += stream.shift_ns;
  if (stream.have && imu.stamp_ns <= stream.last_ns) {
    ++stats_.dropped[imu.stamp_ns == stream.last_ns ? kDropImuDuplicate : kDropImuBackwards];
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
