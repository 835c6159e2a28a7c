#include "io/message_sequencer.h"

#include <algorithm>

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

}  // namespace

MessageSequencer::MessageSequencer(const Options& options, LogReadStats& stats)
    : options_(options), stats_(stats) {}

void MessageSequencer::push(Scan&& scan) {
  if (have_scan_ && scan.stamp_ns <= last_scan_ns_) {
    ++stats_.dropped[scan.stamp_ns == last_scan_ns_ ? kDropScanDuplicate : kDropScanBackwards];
    return;
  }
  have_scan_ = true;
  last_scan_ns_ = scan.stamp_ns;
  const std::int64_t key = scan.stamp_ns + options_.lidar_to_imu_offset_ns;
  if (have_released_ && key < released_key_ns_) {
    ++stats_.dropped[kDropScanLate];
    return;
  }
  insert(key, 1, LogMessage(std::move(scan)));
}

void MessageSequencer::push(const ImuSample& imu) {
  if (!imu.isFinite()) {
    ++stats_.dropped[kDropImuNotFinite];
    return;
  }
  if (have_imu_ && imu.stamp_ns <= last_imu_ns_) {
    ++stats_.dropped[imu.stamp_ns == last_imu_ns_ ? kDropImuDuplicate : kDropImuBackwards];
    return;
  }
  have_imu_ = true;
  last_imu_ns_ = imu.stamp_ns;
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
