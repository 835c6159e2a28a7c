// The `storey` command's progress output (batch/progress_bar.cpp) with a
// clock the test sets: the plain lines written when stderr is not a terminal
// (CI, Slurm logs), and the terminal bar with log messages printed above it.
#include "progress_bar.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace storey::cli {
namespace {

TEST(ProgressLines, OneLinePerStageAndTenPercentStepAndHeartbeat) {
  double now = 0.0;
  std::ostringstream out;
  ProgressBar bar("run", ProgressBar::Mode::kLines, out, [&now] { return now; });
  bar.update(0.0, "odometry");
  now = 1.0;
  bar.update(0.05, "odometry");  // same stage, same 10 % step: no line
  now = 2.0;
  bar.setLogTime(20.0);
  bar.update(0.10, "odometry");
  now = 4.0;
  bar.setLogTime(40.0);
  bar.update(0.15, "odometry");
  now = 5.0;
  bar.print("[info] a log message");
  now = 6.0;
  bar.setLogTime(60.0);
  bar.update(0.20, "odometry");
  now = 40.0;  // 34 s without a line: one more although still at 20-29 %
  bar.setLogTime(100.0);
  bar.update(0.25, "odometry");
  now = 41.0;
  bar.update(1.0, "back end: final optimisation");
  bar.done();
  EXPECT_EQ(out.str(),
            "storey run: odometry 0% (0:00 elapsed, ? left)\n"
            "storey run: odometry 10% (0:02 elapsed, 0:18 left)\n"
            "[info] a log message\n"
            "storey run: odometry 20% (0:06 elapsed, 0:24 left, 10.0x real time)\n"
            "storey run: odometry 25% (0:40 elapsed, 2:00 left, 2.1x real time)\n"
            "storey run: back end: final optimisation 100% (0:41 elapsed, ? left)\n");
}

TEST(ProgressBarOnATerminal, LogMessagesGoAboveTheBarWhichIsRedrawnBelow) {
  double now = 0.0;
  std::ostringstream out;
  ProgressBar bar("run", ProgressBar::Mode::kBar, out, [&now] { return now; });
  bar.update(0.5, "map");
  const std::string drawn = "\r\033[K[############            ]  50% map  0:00 elapsed, ? left";
  EXPECT_EQ(out.str(), drawn);
  out.str("");
  bar.print("[warning] something");
  EXPECT_EQ(out.str(), "\r\033[K[warning] something\n" + drawn)
      << "the bar's line is cleared, the message printed, the bar drawn again";
  out.str("");
  bar.update(0.5, "map");  // nothing changed: no redraw
  EXPECT_EQ(out.str(), "");
  bar.done();
  EXPECT_EQ(out.str(), drawn + "\n") << "the last state stays on screen";
  out.str("");
  bar.print("[info] after the bar");
  EXPECT_EQ(out.str(), "[info] after the bar\n");
}

}  // namespace
}  // namespace storey::cli
