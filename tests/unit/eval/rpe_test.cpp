// RPE over path segments of trajectories with a known scale or heading drift.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "eval/rpe.h"
#include "unit/eval/eval_fixtures.h"

namespace storey::eval {
namespace {

using test::eval::yawPose;

/// Truth: 101 poses 0.5 m apart along x (50 m). The estimate's position is
/// scaled by `scale` and its heading drifts by `yaw_per_metre` [rad/m].
AssociatedPoses straightWalk(double scale, double yaw_per_metre) {
  AssociatedPoses poses;
  for (int i = 0; i <= 100; ++i) {
    const double d = 0.5 * i;
    poses.times.push_back(0.1 * i);
    poses.T_world_gt.push_back(Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(d, 0, 0)));
    poses.T_world_est.push_back(yawPose(yaw_per_metre * d, Eigen::Vector3d(scale * d, 0, 0)));
  }
  poses.est_poses = poses.times.size();
  return poses;
}

TEST(EvalRpe, ConstantScaleErrorGivesThatPercentage) {
  const RpeResult rpe = relativePoseError(straightWalk(1.02, 0.0), 10.0);
  // Starts 0..80 each have a 10 m segment (20 steps of 0.5 m).
  EXPECT_EQ(rpe.translation_percent.count, 81u);
  EXPECT_NEAR(rpe.translation_percent.mean, 2.0, 1e-9);
  EXPECT_NEAR(rpe.translation_percent.max, 2.0, 1e-9);
  EXPECT_NEAR(rpe.rotation_per_metre.max, 0.0, 1e-12);

  const RpeResult short_segments = relativePoseError(straightWalk(0.97, 0.0), 5.0, 2);
  EXPECT_EQ(short_segments.translation_percent.count, 46u);  // starts 0, 2, .., 90
  EXPECT_NEAR(short_segments.translation_percent.median, 3.0, 1e-9);
}

TEST(EvalRpe, ConstantHeadingDriftGivesThatRatePerMetre) {
  const double k = 0.002;  // rad/m
  const RpeResult rpe = relativePoseError(straightWalk(1.0, k), 10.0);
  ASSERT_GT(rpe.rotation_per_metre.count, 0u);
  EXPECT_NEAR(rpe.rotation_per_metre.mean, k, 1e-12);
  EXPECT_NEAR(rpe.rotation_per_metre.max, k, 1e-12);
}

TEST(EvalRpe, PathShorterThanTheSegmentGivesNoSegment) {
  const RpeResult rpe = relativePoseError(straightWalk(1.1, 0.0), 100.0);
  EXPECT_EQ(rpe.translation_percent.count, 0u);
  EXPECT_EQ(rpe.translation_percent.mean, 0.0);
}

TEST(EvalRpe, RejectsBadParameters) {
  EXPECT_THROW(relativePoseError(straightWalk(1.0, 0.0), 0.0), Error);
  EXPECT_THROW(relativePoseError(straightWalk(1.0, 0.0), 10.0, 0), Error);
}

}  // namespace
}  // namespace storey::eval
