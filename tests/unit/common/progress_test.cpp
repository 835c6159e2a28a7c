// ProgressMeter (elapsed, time left, speed) with a clock the test sets, the
// duration and timing texts, and LogRecorder.
#include "common/progress.h"

#include <gtest/gtest.h>

#include <string>

#include "common/log.h"

namespace storey {
namespace {

TEST(ProgressMeter, TimeLeftComesFromTheStagesOwnFractionAndTime) {
  ProgressMeter meter(100.0);  // started at t = 100 s
  meter.update(0.0, "odometry", 100.0);
  meter.update(0.25, "odometry", 110.0);
  const ProgressReading r = meter.reading(110.0);
  EXPECT_EQ(r.stage, "odometry");
  EXPECT_DOUBLE_EQ(r.fraction, 0.25);
  EXPECT_DOUBLE_EQ(r.elapsed, 10.0);
  ASSERT_TRUE(r.left.has_value());
  EXPECT_DOUBLE_EQ(*r.left, 30.0) << "a quarter in 10 s: three quarters in 30 s";
  EXPECT_FALSE(r.speed.has_value()) << "no log time reported";
}

TEST(ProgressMeter, TimeLeftIsUnknownUntilTheStageHasMovedAndRun) {
  ProgressMeter meter(0.0);
  meter.update(0.0, "map", 0.0);
  meter.update(0.5, "map", 0.5);
  EXPECT_FALSE(meter.reading(0.5).left) << "under 1 s of the stage";
  meter.update(0.005, "storeys", 2.0);
  meter.update(0.009, "storeys", 5.0);
  EXPECT_FALSE(meter.reading(5.0).left) << "moved by less than 1 %";
  meter.update(0.105, "storeys", 6.0);
  ASSERT_TRUE(meter.reading(6.0).left);
  EXPECT_NEAR(*meter.reading(6.0).left, 4.0 * 0.895 / 0.1, 1e-9)
      << "measured from the stage's start (t = 2 s, f = 0.005), not the run's";
}

TEST(ProgressMeter, AStageStartingAtItsEndHasNoEstimate) {
  // The pipeline reports "back end: final optimisation" at 1.0 before it runs.
  ProgressMeter meter(0.0);
  meter.update(1.0, "back end: final optimisation", 3.0);
  EXPECT_FALSE(meter.reading(9.0).left);
  EXPECT_DOUBLE_EQ(meter.reading(9.0).elapsed, 9.0);
}

TEST(ProgressMeter, SpeedIsLogTimeOverWallTimeWhileTheStageReadsTheLog) {
  ProgressMeter meter(0.0);
  meter.update(0.1, "odometry", 1.0);
  meter.setLogTime(2.0, 1.0);
  meter.update(0.2, "odometry", 1.5);
  meter.setLogTime(4.0, 1.5);
  EXPECT_FALSE(meter.reading(1.5).speed) << "less than 1 s of log time measured";
  meter.setLogTime(14.0, 5.0);
  ASSERT_TRUE(meter.reading(5.0).speed);
  EXPECT_DOUBLE_EQ(*meter.reading(5.0).speed, 3.0) << "12 s of log in 4 s";
  meter.update(0.0, "map", 6.0);
  EXPECT_FALSE(meter.reading(8.0).speed) << "the map stage does not read the log";
}

TEST(ProgressText, DurationsAndTiming) {
  EXPECT_EQ(formatDuration(0.0), "0:00");
  EXPECT_EQ(formatDuration(7.4), "0:07");
  EXPECT_EQ(formatDuration(754.0), "12:34");
  EXPECT_EQ(formatDuration(3723.0), "1:02:03");
  ProgressReading r;
  r.elapsed = 12.0;
  EXPECT_EQ(timingText(r), "0:12 elapsed, ? left");
  r.left = 18.0;
  r.speed = 2.14;
  EXPECT_EQ(timingText(r), "0:12 elapsed, 0:18 left, 2.1x real time");
}

TEST(LogRecorder, KeepsTheWarningsLoggedWhileItLives) {
  setLogSink([](LogLevel, const std::string&) {});  // quiet
  logWarning("before");
  std::size_t count = 0;
  {
    const LogRecorder recorder;
    logInfo("an info line is not kept");
    logWarning("first");
    logMessage(LogLevel::kError, "second");
    for (std::size_t i = 0; i < LogRecorder::kMaxKept; ++i) logWarning("more");
    count = recorder.warningCount();
    const std::vector<std::string> kept = recorder.warnings();
    ASSERT_EQ(kept.size(), LogRecorder::kMaxKept);
    EXPECT_EQ(kept[0], "first");
    EXPECT_EQ(kept[1], "second");
  }
  EXPECT_EQ(count, LogRecorder::kMaxKept + 2) << "every warning is counted, kept or not";
  logWarning("after: no recorder, no crash");
  setLogSink(nullptr);
}

TEST(Log, FormatLogLine) {
  EXPECT_EQ(formatLogLine(LogLevel::kInfo, "x"), "[info] x");
  EXPECT_EQ(formatLogLine(LogLevel::kWarning, "y"), "[warning] y");
}

}  // namespace
}  // namespace storey
