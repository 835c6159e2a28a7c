// GuardedLogReader (io/imu_guard.h): spikes found and repaired, genuine
// changes of motion left alone, IMU and LiDAR gaps counted with their times,
// saturated runs removed, occluded scans held back, the reader's clock jumps
// reported, messages passed on in their order.
#include "io/imu_guard.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace storey {
namespace {

/// Hands out a fixed list of messages; records `jump` in its stats as it
/// hands out message `jump_at` (as a sequencer would).
class ListReader : public LogReader {
 public:
  explicit ListReader(std::vector<LogMessage> messages, std::size_t jump_at = SIZE_MAX,
                      ClockJump jump = {})
      : messages_(std::move(messages)), jump_at_(jump_at), jump_(jump) {}
  bool next(LogMessage& message) override {
    if (at_ >= messages_.size()) return false;
    if (at_ == jump_at_) stats_.clock_jumps.push_back(jump_);
    message = messages_[at_++];
    return true;
  }
  const LogReadStats& stats() const override { return stats_; }
  std::string describe() const override { return "list"; }

 private:
  std::vector<LogMessage> messages_;
  std::size_t at_ = 0;
  std::size_t jump_at_;
  ClockJump jump_;
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

/// Removes the scans of `in` whose time since the start [s] `drop` picks.
void dropScans(std::vector<LogMessage>& in, const std::function<bool(double)>& drop) {
  in.erase(std::remove_if(in.begin(), in.end(),
                          [&](const LogMessage& m) {
                            return std::holds_alternative<Scan>(m) &&
                                   drop(nsToSeconds(std::get<Scan>(m).stamp_ns - kStart));
                          }),
           in.end());
}

struct Guarded {
  FaultLog faults;
  std::vector<LogMessage> out;
  explicit Guarded(std::vector<LogMessage> in, InputConfig input = {},
                   std::unique_ptr<LogReader> reader_in = nullptr) {
    ImuNoise noise;
    noise.rate_hz = 200.0;
    if (!reader_in) reader_in = std::make_unique<ListReader>(std::move(in));
    GuardedLogReader reader(std::move(reader_in), input, noise, faults);
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

/// The guard counts `count` LiDAR gaps in `in`, the first at `time` [s] for
/// `duration` [s] with `detail` in its text.
void expectLidarGaps(const std::vector<LogMessage>& in, std::int64_t count, double time,
                     double duration, const std::string& detail) {
  Guarded g(in);
  ASSERT_EQ(g.faults.count(kFaultLidarGap), count);
  const FaultEvent& e = g.faults.kinds().at(kFaultLidarGap).first[0];
  EXPECT_NEAR(e.time, time, 1e-9);
  EXPECT_NEAR(e.duration, duration, 1e-9);
  EXPECT_NE(e.detail.find(detail), std::string::npos) << e.detail;
}

TEST(ImuGuard, LidarGapsAreCountedOnceTheScanPeriodIsKnown) {
  std::vector<LogMessage> in = log(8.0);
  // Drop the scans stamped 5.05 to 5.95 s: 10 missing at 10 Hz, 4.95 to 6.05 s without.
  dropScans(in, [](double t) { return t > 5.01 && t < 5.99; });
  expectLidarGaps(in, 1, 4.95, 1.0, "10 scans missing");
}

TEST(ImuGuard, OneDroppedScanIsALidarGap) {
  std::vector<LogMessage> in = log(8.0);
  // Every 10th scan from 3 s on dropped (3.05, 4.05, ...: 5 of them).
  dropScans(in, [](double t) {
    const double frac = t - std::floor(t);
    return t > 3.0 && frac > 0.04 && frac < 0.06;
  });
  expectLidarGaps(in, 5, 2.95, 0.1, "1 scans missing");
}

TEST(ImuGuard, ASaturatedRunIsRemovedAndTheSampleAfterItMarked) {
  // 0.2 s from 2.0 s with gyro x stuck at 34.9 rad/s (2000 deg/s) while the
  // other axes go on; one sample at the range alone is a spike, not a run;
  // two samples stuck at 5 rad/s (fewer than three) are left alone.
  Guarded g(log(5.0, [](ImuSample& s) {
    const double t = nsToSeconds(s.stamp_ns - kStart);
    if (t > 2.0 - 1e-9 && t < 2.2 - 1e-9) s.gyro.x() = 34.9;
    if (std::abs(t - 3.0) < 1e-9) s.gyro = Eigen::Vector3d(34.9, -34.9, 34.9);
    if (std::abs(t - 4.0) < 1e-9 || std::abs(t - 4.005) < 1e-9) s.gyro.y() = 5.0;
    s.accel.x() = 0.1 * t;  // the other axes still change
    return true;
  }));
  ASSERT_EQ(g.faults.count(kFaultImuSaturation), 1);
  const FaultEvent& e = g.faults.kinds().at(kFaultImuSaturation).first[0];
  EXPECT_NEAR(e.time, 2.0, 1e-9);
  EXPECT_NEAR(e.duration, 0.2, 1e-9);
  EXPECT_NE(e.detail.find("40 samples stuck at gyro x 34.9 rad/s"), std::string::npos) << e.detail;
  EXPECT_EQ(g.faults.count(kFaultImuSpike), 1);
  EXPECT_EQ(g.faults.count(kFaultImuGap), 0);  // the removal is not reported again as a gap
  const std::vector<ImuSample> samples = g.imu();
  EXPECT_EQ(samples.size(), 1001u - 40u);
  int marked = 0;
  for (const ImuSample& s : samples) {
    const double t = nsToSeconds(s.stamp_ns - kStart);
    EXPECT_FALSE(t > 2.0 - 1e-9 && t < 2.2 - 1e-9) << t;
    if (s.after_removed) {
      ++marked;
      EXPECT_NEAR(t, 2.2, 1e-9);
    }
    if (std::abs(t - 4.0) < 1e-9) {
      EXPECT_EQ(s.gyro.y(), 5.0);
    }
  }
  EXPECT_EQ(marked, 1);
  // The scans read during the run are passed on, in time order.
  std::int64_t last = 0;
  std::size_t scans = 0;
  for (const LogMessage& m : g.out) {
    EXPECT_GE(stampOf(m), last);
    last = stampOf(m);
    scans += std::holds_alternative<Scan>(m);
  }
  EXPECT_EQ(scans, 50u);
}

TEST(ImuGuard, AnAccelerometerStuckAtItsRangeIsSaturationAndTheCheckCanBeOff) {
  const auto stuck = [](ImuSample& s) {
    const double t = nsToSeconds(s.stamp_ns - kStart);
    if (t > 1.0 - 1e-9 && t < 1.02 - 1e-9) s.accel.z() = -19.62;  // 4 samples at -2 g
    return true;
  };
  Guarded g(log(2.0, stuck));
  ASSERT_EQ(g.faults.count(kFaultImuSaturation), 1);
  EXPECT_EQ(g.imu().size(), 401u - 4u);
  InputConfig off;
  off.imu_saturation_gyro = 0.0;
  off.imu_saturation_accel = 0.0;
  Guarded unchecked(log(2.0, stuck), off);
  EXPECT_EQ(unchecked.faults.count(kFaultImuSaturation), 0);
  EXPECT_EQ(unchecked.imu().size(), 401u);
  // A run at the end of the log is removed as well.
  Guarded at_end(log(2.0, [](ImuSample& s) {
    if (s.stamp_ns >= kStart + secondsToNs(1.9)) s.gyro.z() = -8.0;
    return true;
  }));
  ASSERT_EQ(at_end.faults.count(kFaultImuSaturation), 1);
  EXPECT_NEAR(at_end.faults.kinds().at(kFaultImuSaturation).first[0].time, 1.9, 1e-9);
}

/// A scan of `far` points 5 m away and `near` points 0.35 m away.
Scan scanWith(double t, int far, int near) {
  Scan s = scan(t);
  for (int i = 0; i < far + near; ++i) {
    ScanPoint p;
    const double a = 0.01 * i;
    p.p = Eigen::Vector3f(std::cos(a), std::sin(a), 0.0f) * (i < far ? 5.0f : 0.35f);
    s.points.push_back(p);
  }
  return s;
}

/// Scans at 10 Hz from 0 to `end` s (IMU at 200 Hz between): 1000 points
/// beyond 0.5 m each, except in [from, to], where only `far` of them are
/// and 700 are at 0.35 m.
std::vector<LogMessage> occludedLog(double end, double from, double to, int far) {
  std::vector<LogMessage> out;
  for (int k = 0; k * 0.005 <= end + 1e-9; ++k) {
    out.emplace_back(imu(k * 0.005));
    if (k % 20 != 10) continue;
    const double t = k * 0.005;
    const bool occluded = t > from - 1e-9 && t < to + 1e-9;
    out.emplace_back(occluded ? scanWith(t, far, 700) : scanWith(t, 1000 - (k % 40), 0));
  }
  return out;
}

/// Time [s since the start] and point count of each scan passed on.
std::vector<std::pair<double, std::size_t>> scansOut(const std::vector<LogMessage>& messages) {
  std::vector<std::pair<double, std::size_t>> scans;
  for (const LogMessage& m : messages)
    if (const auto* s = std::get_if<Scan>(&m))
      scans.emplace_back(nsToSeconds(s->stamp_ns - kStart), s->points.size());
  return scans;
}

TEST(ImuGuard, OccludedScansLoseTheirNearPointsAndCountAsOneEvent) {
  // 2.05 to 3.95 s: 20 scans with 250 of the usual ~1000 points beyond 0.5 m
  // and 700 at 0.35 m (a body): passed on with the 250 only.
  Guarded g(occludedLog(6.0, 2.0, 4.0, 250));
  ASSERT_EQ(g.faults.count(kFaultLidarOccluded), 1);
  const FaultEvent& e = g.faults.kinds().at(kFaultLidarOccluded).first[0];
  EXPECT_NEAR(e.time, 2.05, 1e-9);
  EXPECT_NEAR(e.duration, 2.0, 1e-9);  // to the next clear scan
  EXPECT_NE(e.detail.find("20 scans with 25 % of the usual points"), std::string::npos) << e.detail;
  EXPECT_NE(e.detail.find("0 skipped"), std::string::npos) << e.detail;
  const auto scans = scansOut(g.out);
  ASSERT_EQ(scans.size(), 60u);
  for (const auto& [t, points] : scans) {
    if (t > 2.0 && t < 4.0) {
      EXPECT_EQ(points, 250u) << t;
    } else {
      EXPECT_GE(points, 960u) << t;
    }
  }
  // 50 left (5 %): too little to register, those scans are skipped.
  Guarded blind(occludedLog(6.0, 2.0, 4.0, 50));
  ASSERT_EQ(blind.faults.count(kFaultLidarOccluded), 1);
  EXPECT_NE(blind.faults.kinds().at(kFaultLidarOccluded).first[0].detail.find("20 skipped"),
            std::string::npos);
  EXPECT_EQ(scansOut(blind.out).size(), 40u);
  // 600 of ~1000 (above 40 %) is not an occlusion; with the check off nothing changes.
  EXPECT_EQ(Guarded(occludedLog(6.0, 2.0, 4.0, 600)).faults.count(kFaultLidarOccluded), 0);
  InputConfig off;
  off.lidar_occlusion_fraction = 0.0;
  Guarded unchecked(occludedLog(6.0, 2.0, 4.0, 50), off);
  EXPECT_EQ(unchecked.faults.count(kFaultLidarOccluded), 0);
  const auto all = scansOut(unchecked.out);
  ASSERT_EQ(all.size(), 60u);
  EXPECT_EQ(all[25].second, 750u);  // 2.55 s: 50 + 700
}

TEST(ImuGuard, ALastingDropInPointsIsLearntAfterFiveSeconds) {
  // From 2 s to the end (10 s) a quarter of the points: occluded for 5 s,
  // then the new count is the usual one and the scans are passed on whole.
  Guarded g(occludedLog(10.0, 2.0, 11.0, 250));
  ASSERT_EQ(g.faults.count(kFaultLidarOccluded), 1);
  const FaultEvent& e = g.faults.kinds().at(kFaultLidarOccluded).first[0];
  EXPECT_NEAR(e.time, 2.05, 1e-9);
  EXPECT_NEAR(e.duration, 5.1, 1e-9);
  const auto scans = scansOut(g.out);
  ASSERT_EQ(scans.size(), 100u);
  for (const auto& [t, points] : scans) {
    if (t > 2.0 && t < 7.1) {
      EXPECT_EQ(points, 250u) << t;
    } else if (t > 7.1) {
      EXPECT_EQ(points, 950u) << t;
    }
  }
}

TEST(ImuGuard, TheReadersClockJumpsAreReported) {
  std::vector<LogMessage> in = log(3.0);
  const ClockJump jump{true, kStart + secondsToNs(1.5), -secondsToNs(2.0)};
  Guarded g({}, {}, std::make_unique<ListReader>(in, 300, jump));
  ASSERT_EQ(g.faults.count(kFaultClockJump), 1);
  const FaultEvent& e = g.faults.kinds().at(kFaultClockJump).first[0];
  EXPECT_NEAR(e.time, 1.5, 1e-9);
  EXPECT_EQ(e.detail, "IMU stamps jumped by -2.000 s");
  EXPECT_EQ(g.out.size(), in.size());
}

}  // namespace
}  // namespace storey
