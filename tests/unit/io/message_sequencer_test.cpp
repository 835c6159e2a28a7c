// Time ordering of scans and IMU samples read in record order.
#include "io/message_sequencer.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>

namespace storey {
namespace {

constexpr std::int64_t kMs = 1'000'000;

ImuSample imu(std::int64_t stamp_ns) {
  ImuSample s;
  s.stamp_ns = stamp_ns;
  s.accel = Eigen::Vector3d(0, 0, 9.81);
  return s;
}

Scan scan(std::int64_t stamp_ns, int points = 3) {
  Scan s;
  s.stamp_ns = stamp_ns;
  s.points.resize(points);
  return s;
}

/// Stamp of each message and 's' or 'i', in delivery order.
std::vector<std::pair<char, std::int64_t>> drain(MessageSequencer& sequencer) {
  std::vector<std::pair<char, std::int64_t>> out;
  LogMessage m;
  sequencer.finish();
  while (sequencer.pop(m)) {
    if (const auto* s = std::get_if<Scan>(&m)) {
      out.emplace_back('s', s->stamp_ns);
    } else {
      out.emplace_back('i', std::get<ImuSample>(m).stamp_ns);
    }
  }
  return out;
}

TEST(IoMessageSequencer, ScansRecordedLateAreMovedBeforeLaterImu) {
  LogReadStats stats;
  MessageSequencer sequencer({}, stats);
  // Record order: IMU 0..40 ms, then the scan stamped 10 ms (recorded at the end of its sweep).
  for (int t = 0; t <= 40; t += 10) sequencer.push(imu(t * kMs));
  sequencer.push(scan(10 * kMs));
  sequencer.push(imu(50 * kMs));
  const auto out = drain(sequencer);
  const std::vector<std::pair<char, std::int64_t>> expected = {
      {'i', 0},        {'i', 10 * kMs}, {'s', 10 * kMs}, {'i', 20 * kMs},
      {'i', 30 * kMs}, {'i', 40 * kMs}, {'i', 50 * kMs}};
  EXPECT_EQ(out, expected);
  EXPECT_EQ(stats.scans, 1);
  EXPECT_EQ(stats.imu_samples, 6);
  EXPECT_EQ(stats.points, 3);
  EXPECT_TRUE(stats.dropped.empty());
}

TEST(IoMessageSequencer, LidarToImuOffsetOrdersButKeepsStamp) {
  LogReadStats stats;
  MessageSequencer::Options options;
  options.lidar_to_imu_offset_ns = 25 * kMs;  // t_imu = t_lidar + 25 ms
  MessageSequencer sequencer(options, stats);
  sequencer.push(imu(0));
  sequencer.push(imu(20 * kMs));
  sequencer.push(imu(30 * kMs));
  sequencer.push(scan(0));  // at 25 ms in the IMU clock
  const auto out = drain(sequencer);
  const std::vector<std::pair<char, std::int64_t>> expected = {
      {'i', 0}, {'i', 20 * kMs}, {'s', 0}, {'i', 30 * kMs}};
  EXPECT_EQ(out, expected);
}

TEST(IoMessageSequencer, LateImuPutInOrderDuplicateAndNonFiniteDropped) {
  LogReadStats stats;
  MessageSequencer sequencer({}, stats);
  sequencer.push(imu(10 * kMs));
  sequencer.push(imu(20 * kMs));
  sequencer.push(imu(15 * kMs));  // recorded late: put back in order
  sequencer.push(imu(20 * kMs));  // duplicate of the newest
  sequencer.push(imu(15 * kMs));  // duplicate of one waiting in the buffer
  ImuSample bad = imu(25 * kMs);
  bad.gyro.x() = std::numeric_limits<double>::quiet_NaN();
  sequencer.push(bad);
  ImuSample inf = imu(26 * kMs);
  inf.accel.z() = std::numeric_limits<double>::infinity();
  sequencer.push(inf);
  sequencer.push(imu(30 * kMs));
  const auto out = drain(sequencer);
  const std::vector<std::pair<char, std::int64_t>> expected = {
      {'i', 10 * kMs}, {'i', 15 * kMs}, {'i', 20 * kMs}, {'i', 30 * kMs}};
  EXPECT_EQ(out, expected);
  EXPECT_EQ(stats.reordered, 1);
  EXPECT_EQ(stats.dropped[kDropImuBackwards], 0);
  EXPECT_EQ(stats.dropped[kDropImuDuplicate], 2);
  EXPECT_EQ(stats.dropped[kDropImuNotFinite], 2);
  EXPECT_EQ(stats.imu_samples, 4);
}

TEST(IoMessageSequencer, ScansTooLateToPlaceAndDuplicatesDropped) {
  LogReadStats stats;
  MessageSequencer sequencer({}, stats);
  std::vector<std::int64_t> out;
  LogMessage m;
  const auto popReady = [&] {
    while (sequencer.pop(m)) out.push_back(std::get<Scan>(m).stamp_ns);
  };
  sequencer.push(scan(100 * kMs));
  sequencer.push(scan(100 * kMs));  // duplicate
  sequencer.push(scan(50 * kMs));   // late but nothing later released yet: put in place
  sequencer.push(scan(1200 * kMs));
  popReady();                      // 50 and 100 are out (a window older than 1200)
  sequencer.push(scan(80 * kMs));  // older than what was released: dropped
  sequencer.push(scan(1300 * kMs));
  sequencer.finish();
  popReady();
  EXPECT_EQ(out, (std::vector<std::int64_t>{50 * kMs, 100 * kMs, 1200 * kMs, 1300 * kMs}));
  EXPECT_EQ(stats.dropped[kDropScanDuplicate], 1);
  EXPECT_EQ(stats.dropped[kDropScanBackwards], 1);
  EXPECT_EQ(stats.reordered, 1);
}

TEST(IoMessageSequencer, BufferIsBoundedByWindowAndCount) {
  LogReadStats stats;
  MessageSequencer::Options options;
  options.window_ns = 100 * kMs;
  options.max_buffered = 50;
  MessageSequencer sequencer(options, stats);
  LogMessage m;
  std::size_t most = 0;
  for (int k = 0; k < 1000; ++k) {
    sequencer.push(imu(k * 2 * kMs));  // 500 Hz
    while (sequencer.pop(m)) {
    }
    most = std::max(most, sequencer.buffered());
  }
  EXPECT_LE(most, 51u);  // 100 ms of 500 Hz
  EXPECT_GT(stats.imu_samples, 900);

  // Count bound: every message at the same key, nothing ever leaves by the window.
  LogReadStats stats2;
  options.window_ns = std::numeric_limits<std::int64_t>::max();
  MessageSequencer by_count(options, stats2);
  for (int k = 0; k < 200; ++k) {
    by_count.push(scan(k + 1));
    while (by_count.pop(m)) {
    }
    ASSERT_LE(by_count.buffered(), 50u);
  }
}

TEST(IoMessageSequencer, MessagesLaterThanTheWindowAreDropped) {
  LogReadStats stats;
  MessageSequencer::Options options;
  options.window_ns = 100 * kMs;
  MessageSequencer sequencer(options, stats);
  LogMessage m;
  for (int t = 0; t <= 500; t += 10) {
    sequencer.push(imu(t * kMs));
    while (sequencer.pop(m)) {
    }
  }
  sequencer.push(scan(100 * kMs));  // 400 ms late: older than what was already delivered
  const auto out = drain(sequencer);
  for (const auto& [kind, stamp] : out) EXPECT_EQ(kind, 'i');
  EXPECT_EQ(stats.dropped[kDropScanLate], 1);
  EXPECT_EQ(stats.scans, 0);
}

TEST(IoMessageSequencer, DeliveryIsMonotonic) {
  LogReadStats stats;
  MessageSequencer sequencer({}, stats);
  // Scans recorded 80 ms after their stamp, IMU 2 ms after: 5 s of 400 Hz + 10 Hz.
  std::vector<std::pair<std::int64_t, LogMessage>> by_record;
  for (std::int64_t k = 0; k < 2000; ++k) {
    by_record.emplace_back(k * 2'500'000 + 2 * kMs, imu(k * 2'500'000));
  }
  for (std::int64_t k = 0; k < 50; ++k) {
    by_record.emplace_back(k * 100 * kMs + 80 * kMs, scan(k * 100 * kMs));
  }
  std::stable_sort(by_record.begin(), by_record.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  LogMessage m;
  std::int64_t last = std::numeric_limits<std::int64_t>::min();
  int delivered = 0;
  for (auto& [record, message] : by_record) {
    if (auto* s = std::get_if<Scan>(&message)) {
      sequencer.push(std::move(*s));
    } else {
      sequencer.push(std::get<ImuSample>(message));
    }
    while (sequencer.pop(m)) {
      const std::int64_t stamp = std::visit([](const auto& x) { return x.stamp_ns; }, m);
      ASSERT_GE(stamp, last);
      last = stamp;
      ++delivered;
    }
  }
  delivered += static_cast<int>(drain(sequencer).size());
  EXPECT_EQ(delivered, 2050);
  EXPECT_TRUE(stats.dropped.empty());
}

/// A log in record order: IMU at 200 Hz recorded at its true time, scans at
/// 10 Hz recorded at the end of their sweep (0.1 s after their start), from
/// 0 to `end_ms`; `imu_stamp` and `scan_stamp` map a true time to the stamp
/// written (a clock jump), -1: the message is missing. Returns what the
/// sequencer delivers.
std::vector<std::pair<char, std::int64_t>> recordOrder(
    MessageSequencer& sequencer, std::int64_t end_ms,
    const std::function<std::int64_t(std::int64_t)>& imu_stamp,
    const std::function<std::int64_t(std::int64_t)>& scan_stamp) {
  std::vector<std::pair<char, std::int64_t>> out;
  LogMessage m;
  const auto take = [&] {
    while (sequencer.pop(m)) {
      if (const auto* s = std::get_if<Scan>(&m)) {
        out.emplace_back('s', s->stamp_ns);
      } else {
        out.emplace_back('i', std::get<ImuSample>(m).stamp_ns);
      }
    }
  };
  for (std::int64_t t = 0; t <= end_ms * kMs; t += 5 * kMs) {
    if (t % (100 * kMs) == 0 && t >= 100 * kMs) {
      const std::int64_t stamp = scan_stamp(t - 100 * kMs);
      if (stamp >= 0) sequencer.push(scan(stamp));
    }
    const std::int64_t stamp = imu_stamp(t);
    if (stamp >= 0) sequencer.push(imu(stamp));
    take();
  }
  sequencer.finish();
  take();
  return out;
}

std::int64_t same(std::int64_t t) {
  return t;
}

/// The stamps of one stream ('i' or 's') delivered.
std::vector<std::int64_t> stampsOf(const std::vector<std::pair<char, std::int64_t>>& out,
                                   char kind) {
  std::vector<std::int64_t> stamps;
  for (const auto& [k, stamp] : out)
    if (k == kind) stamps.push_back(stamp);
  return stamps;
}

TEST(IoMessageSequencer, AnImuClockJumpIsMeasuredAndUndone) {
  for (const std::int64_t jump : {2000 * kMs, -1500 * kMs, 500 * kMs, -450 * kMs}) {
    LogReadStats stats;
    MessageSequencer sequencer({}, stats);
    const auto out = recordOrder(
        sequencer, 6000, [&](std::int64_t t) { return t >= 3000 * kMs ? t + jump : t; }, same);
    ASSERT_EQ(stats.clock_jumps.size(), 1u) << jump;
    EXPECT_TRUE(stats.clock_jumps[0].imu);
    EXPECT_EQ(stats.clock_jumps[0].stamp_ns, 3000 * kMs);
    EXPECT_EQ(stats.clock_jumps[0].step_ns, jump);
    // Every sample delivered, at its true stamp, nothing dropped.
    const auto imu_stamps = stampsOf(out, 'i');
    ASSERT_EQ(imu_stamps.size(), 1201u) << jump;
    for (std::size_t k = 0; k < imu_stamps.size(); ++k)
      EXPECT_EQ(imu_stamps[k], static_cast<std::int64_t>(k) * 5 * kMs);
    EXPECT_EQ(stampsOf(out, 's').size(), 60u);
    EXPECT_TRUE(stats.dropped.empty());
  }
}

TEST(IoMessageSequencer, ALidarClockJumpIsMeasuredAndUndone) {
  for (const std::int64_t jump : {1500 * kMs, -500 * kMs}) {
    LogReadStats stats;
    MessageSequencer sequencer({}, stats);
    const auto out = recordOrder(sequencer, 6000, same,
                                 [&](std::int64_t t) { return t >= 3000 * kMs ? t + jump : t; });
    ASSERT_EQ(stats.clock_jumps.size(), 1u) << jump;
    EXPECT_FALSE(stats.clock_jumps[0].imu);
    EXPECT_EQ(stats.clock_jumps[0].stamp_ns, 3000 * kMs);
    EXPECT_EQ(stats.clock_jumps[0].step_ns, jump);
    const auto scan_stamps = stampsOf(out, 's');
    ASSERT_EQ(scan_stamps.size(), 60u) << jump;
    for (std::size_t k = 0; k < scan_stamps.size(); ++k)
      EXPECT_EQ(scan_stamps[k], static_cast<std::int64_t>(k) * 100 * kMs);
    EXPECT_TRUE(stats.dropped.empty());
  }
}

TEST(IoMessageSequencer, GapsPausesAndAGarbledStampAreNotClockJumps) {
  const auto missing = [](std::int64_t from_ms, std::int64_t to_ms) {
    return [=](std::int64_t t) { return t >= from_ms * kMs && t < to_ms * kMs ? -1 : t; };
  };
  {  // one second without IMU: the scans go on, so the lead stays
    LogReadStats stats;
    MessageSequencer sequencer({}, stats);
    const auto out = recordOrder(sequencer, 6000, missing(3000, 4000), same);
    EXPECT_TRUE(stats.clock_jumps.empty());
    EXPECT_EQ(stampsOf(out, 'i').size(), 1201u - 200u);
  }
  {  // one second without scans
    LogReadStats stats;
    MessageSequencer sequencer({}, stats);
    const auto out = recordOrder(sequencer, 6000, same, missing(3000, 4000));
    EXPECT_TRUE(stats.clock_jumps.empty());
    EXPECT_EQ(stampsOf(out, 's').size(), 50u);
  }
  {  // both streams pause for a second: whichever resumes first stepped, but so does the other
    LogReadStats stats;
    MessageSequencer sequencer({}, stats);
    recordOrder(sequencer, 6000, missing(3000, 4000), missing(2900, 3900));
    EXPECT_TRUE(stats.clock_jumps.empty());
  }
  {  // one IMU sample stamped 2 s early: dropped as before, the stream is not moved
    LogReadStats stats;
    MessageSequencer sequencer({}, stats);
    const auto out = recordOrder(
        sequencer, 6000, [](std::int64_t t) { return t == 3000 * kMs ? t - 2000 * kMs : t; }, same);
    EXPECT_TRUE(stats.clock_jumps.empty());
    EXPECT_EQ(stampsOf(out, 'i').size(), 1200u);
    EXPECT_EQ(stats.dropped[kDropImuBackwards], 1);
  }
}

TEST(IoMessageSequencer, StampsAtTheEndsOfTheirRangeDoNotOverflowTheJumpChecks) {
  // A ROS 1 stamp is 0..2^32 s (up to 4.3e18 ns): an IMU stream that jumps
  // to the end of that range and back while the scans stay put, then the
  // scans jump there; sums of three such stamps exceed int64 (the asan
  // build's UBSan would stop at one). Such a step is a jump (a clock set
  // from 1970 to today by a late time sync is one).
  const std::int64_t far = std::int64_t{4'294'967'295} * 1'000'000'000 + 999'999'999;
  LogReadStats stats;
  MessageSequencer sequencer({}, stats);
  const auto out = recordOrder(
      sequencer, 6000,
      [&](std::int64_t t) {
        if (t >= 2000 * kMs && t < 3000 * kMs) return far - (3000 * kMs - t);
        if (t >= 4000 * kMs && t < 4500 * kMs) return t / 1000;
        return t;
      },
      [&](std::int64_t t) { return t >= 5000 * kMs ? far - 1000 * kMs + t : t; });
  EXPECT_FALSE(stats.clock_jumps.empty());
  // Everything delivered is in time order.
  for (std::size_t k = 1; k < out.size(); ++k) EXPECT_LE(out[k - 1].second, out[k].second);
}

}  // namespace
}  // namespace storey
