// GuardedLogReader (io/imu_guard.h): spikes found and repaired, genuine
// changes of motion left alone, IMU and LiDAR gaps counted with their times,
// messages passed on in their order.
#include "io/imu_guard.h"

#include <gtest/gtest.h>

#include <vector>

namespace storey {
namespace {

/// Hands out a fixed list of messages.
class ListReader : public LogReader {
 public:
  explicit ListReader(std::vector<LogMessage> messages) : messages_(std::move(messages)) {}
  bool next(LogMessage& message) override {
    if (at_ >= messages_.size()) return false;
    message = messages_[at_++];
    return true;
  }
  const LogReadStats& stats() const override { return stats_; }
  std::string describe() const override { return "list"; }

 private:
  std::vector<LogMessage> messages_;
  std::size_t at_ = 0;
  LogReadStats stats_;
};

constexpr std::int64_t kStart = 1'000'000'000'000;

ImuSample imu(double t, const Eigen::Vector3d& gyro = Eigen::Vector3d(0.1, 0.0, 0.2),
              const Eigen::Vector3d& accel = Eigen::Vector3d(0.0, 0.3, 9.8)) {
  ImuSample s;
  s.stamp_ns = kStart + secondsToNs(t);
  s.gyro = gyro;
  s.accel = accel;
  return s;
}

Scan scan(double t) {
  Scan s;
  s.stamp_ns = kStart + secondsToNs(t);
  return s;
}

/// 200 Hz IMU from 0 to `end` s, scans at 10 Hz; `edit` may change or drop samples.
std::vector<LogMessage> log(double end, const std::function<bool(ImuSample&)>& edit = {}) {
  std::vector<LogMessage> out;
  for (int k = 0; k * 0.005 <= end + 1e-9; ++k) {
    ImuSample s = imu(k * 0.005);
    if (!edit || edit(s)) out.emplace_back(s);
    if (k % 20 == 10) out.emplace_back(scan(k * 0.005));
  }
  return out;
}

struct Guarded {
  FaultLog faults;
  std::vector<LogMessage> out;
  explicit Guarded(std::vector<LogMessage> in, InputConfig input = {}) {
    ImuNoise noise;
    noise.rate_hz = 200.0;
    GuardedLogReader reader(std::make_unique<ListReader>(std::move(in)), input, noise, faults);
    LogMessage m;
    while (reader.next(m)) out.push_back(m);
  }
  std::vector<ImuSample> imu() const {
    std::vector<ImuSample> samples;
    for (const auto& m : out)
      if (auto* s = std::get_if<ImuSample>(&m)) samples.push_back(*s);
    return samples;
  }
};

std::int64_t stampOf(const LogMessage& m) {
  return std::holds_alternative<Scan>(m) ? std::get<Scan>(m).stamp_ns
                                         : std::get<ImuSample>(m).stamp_ns;
}

TEST(ImuGuard, ACleanLogPassesUnchangedAndInOrder) {
  const std::vector<LogMessage> in = log(5.0);
  Guarded g(in);
  ASSERT_EQ(g.out.size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(stampOf(g.out[i]), stampOf(in[i])) << i;
    EXPECT_EQ(g.out[i].index(), in[i].index()) << i;
  }
  EXPECT_TRUE(g.faults.kinds().empty());
}

TEST(ImuGuard, ASaturatedSampleIsReplacedByItsNeighboursAndCounted) {
  Guarded g(log(5.0, [](ImuSample& s) {
    if (s.stamp_ns == kStart + secondsToNs(2.0) || s.stamp_ns == kStart + secondsToNs(3.5)) {
      s.gyro = Eigen::Vector3d(34.9, -34.9, 34.9);
      s.accel = Eigen::Vector3d(156.9, -156.9, 156.9);
    }
    return true;
  }));
  ASSERT_EQ(g.faults.count(kFaultImuSpike), 2);
  const auto& events = g.faults.kinds().at(kFaultImuSpike).first;
  EXPECT_NEAR(events[0].time, 2.0, 1e-9);
  EXPECT_NEAR(events[1].time, 3.5, 1e-9);
  for (const ImuSample& s : g.imu()) {
    EXPECT_NEAR((s.gyro - Eigen::Vector3d(0.1, 0.0, 0.2)).norm(), 0.0, 1e-12) << s.stamp_ns;
    EXPECT_NEAR((s.accel - Eigen::Vector3d(0.0, 0.3, 9.8)).norm(), 0.0, 1e-12) << s.stamp_ns;
  }
}

TEST(ImuGuard, AGarbledForceAloneIsASpikeButAStepInTheMotionIsNot) {
  // One sample's force 70 m/s^2 off: a spike. A turn starting (the rate
  // stepping by 12 rad/s and staying there): not a spike, whatever its size.
  Guarded g(log(3.0, [](ImuSample& s) {
    if (s.stamp_ns == kStart + secondsToNs(1.0)) s.accel.z() += 70.0;
    if (s.stamp_ns >= kStart + secondsToNs(2.0)) s.gyro.z() += 12.0;
    return true;
  }));
  EXPECT_EQ(g.faults.count(kFaultImuSpike), 1);
  // With the checks off (0), nothing is changed.
  InputConfig off;
  off.imu_spike_gyro = 0.0;
  off.imu_spike_accel = 0.0;
  Guarded unchecked(log(3.0,
                        [](ImuSample& s) {
                          if (s.stamp_ns == kStart + secondsToNs(1.0)) s.accel.z() += 70.0;
                          return true;
                        }),
                    off);
  EXPECT_EQ(unchecked.faults.count(kFaultImuSpike), 0);
}

TEST(ImuGuard, ImuGapsAreCountedWithTheirTimeAndLength) {
  // 0.5 s without samples from 2.0 s, 1.2 s from 4.0 s; a 30 ms hiccup (below
  // the 50 ms threshold) is not a gap.
  Guarded g(log(8.0, [](ImuSample& s) {
    const double t = nsToSeconds(s.stamp_ns - kStart);
    return !(t > 2.0 + 1e-9 && t < 2.5 - 1e-9) && !(t > 4.0 + 1e-9 && t < 5.2 - 1e-9) &&
           !(t > 6.0 + 1e-9 && t < 6.03 - 1e-9);
  }));
  ASSERT_EQ(g.faults.count(kFaultImuGap), 2);
  const FaultKindSummary& gaps = g.faults.kinds().at(kFaultImuGap);
  EXPECT_NEAR(gaps.first[0].time, 2.0, 1e-9);
  EXPECT_NEAR(gaps.first[0].duration, 0.5, 1e-9);
  EXPECT_NEAR(gaps.first[1].time, 4.0, 1e-9);
  EXPECT_NEAR(gaps.first[1].duration, 1.2, 1e-9);
  EXPECT_NEAR(gaps.total_duration, 1.7, 1e-9);
  EXPECT_EQ(g.faults.count(kFaultImuSpike), 0);  // no spike across a gap
}

TEST(ImuGuard, LidarGapsAreCountedOnceTheScanPeriodIsKnown) {
  std::vector<LogMessage> in = log(8.0);
  // Drop the scans stamped 5.05 to 5.95 s: 10 missing at 10 Hz, 4.95 to 6.05 s without.
  in.erase(std::remove_if(in.begin(), in.end(),
                          [](const LogMessage& m) {
                            if (!std::holds_alternative<Scan>(m)) return false;
                            const double t = nsToSeconds(std::get<Scan>(m).stamp_ns - kStart);
                            return t > 5.01 && t < 5.99;
                          }),
           in.end());
  Guarded g(in);
  ASSERT_EQ(g.faults.count(kFaultLidarGap), 1);
  const FaultEvent& e = g.faults.kinds().at(kFaultLidarGap).first[0];
  EXPECT_NEAR(e.time, 4.95, 1e-9);
  EXPECT_NEAR(e.duration, 1.0, 1e-9);
  EXPECT_NE(e.detail.find("10 scans missing"), std::string::npos) << e.detail;
}

}  // namespace
}  // namespace storey
