// core/backend/solve_schedule: when the whole graph is solved.
#include "backend/solve_schedule.h"

#include <gtest/gtest.h>

namespace storey::backend {
namespace {

/// Keyframes solved in whole-graph solves per keyframe over a walk of
/// `keyframes` keyframes, one optimisation per keyframe.
double wholeGraphWorkPerKeyframe(const GraphConfig& config, int keyframes) {
  double work = 0.0;
  int since = -1;
  for (int k = 1; k <= keyframes; ++k) {
    const bool whole = wholeGraphSolveDue(config, since, k);
    if (whole) work += k;
    since = whole ? 1 : since + 1;
  }
  return work / keyframes;
}

TEST(SolveSchedule, FullEveryForSmallGraphsThenAShareOfTheGraph) {
  const GraphConfig config;  // full_every 25, full_every_share 0.04
  EXPECT_EQ(wholeGraphInterval(config, 10), 25);
  EXPECT_EQ(wholeGraphInterval(config, 625), 25);
  EXPECT_EQ(wholeGraphInterval(config, 626), 26);
  EXPECT_EQ(wholeGraphInterval(config, 2000), 80);
  GraphConfig fixed;
  fixed.full_every_share = 0.0;
  EXPECT_EQ(wholeGraphInterval(fixed, 100000), 25);
}

TEST(SolveSchedule, FirstSolveAndNoWindowAreWholeGraph) {
  GraphConfig config;
  EXPECT_TRUE(wholeGraphSolveDue(config, -1, 2));
  EXPECT_FALSE(wholeGraphSolveDue(config, 1, 2));
  EXPECT_FALSE(wholeGraphSolveDue(config, 24, 100));
  EXPECT_TRUE(wholeGraphSolveDue(config, 25, 100));
  config.window_keyframes = 0;
  EXPECT_TRUE(wholeGraphSolveDue(config, 1, 100));
}

TEST(SolveSchedule, WholeGraphWorkPerKeyframeDoesNotGrowWithTheWalk) {
  const GraphConfig config;
  const double short_walk = wholeGraphWorkPerKeyframe(config, 5000);
  const double long_walk = wholeGraphWorkPerKeyframe(config, 50000);
  EXPECT_LT(short_walk, 1.1 / config.full_every_share);
  EXPECT_LT(long_walk, 1.1 / config.full_every_share);
  EXPECT_NEAR(long_walk, short_walk, 0.1 * short_walk);
  // A fixed interval grows with the walk: ten times the keyframes, ten times the work.
  GraphConfig fixed;
  fixed.full_every_share = 0.0;
  EXPECT_GT(wholeGraphWorkPerKeyframe(fixed, 50000), 9.0 * wholeGraphWorkPerKeyframe(fixed, 5000));
}

}  // namespace
}  // namespace storey::backend
