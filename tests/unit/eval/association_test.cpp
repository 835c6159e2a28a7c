// Association by timestamp: interpolation of the truth, tolerances, gaps and
// clocks that do not agree.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "eval/association.h"
#include "unit/eval/eval_fixtures.h"

namespace storey::eval {
namespace {

using test::eval::yawPose;

/// Constant velocity (1, 0.5, 0.1) m/s and yaw rate 0.3 rad/s from t0: exactly
/// what linear interpolation and slerp reproduce between any two samples.
Pose uniformMotion(double t, double t0) {
  const double s = t - t0;
  return yawPose(0.3 * s, Eigen::Vector3d(1.0 * s, 0.5 * s, 0.1 * s));
}

Trajectory sampled(double t0, double rate, int n, double motion_t0) {
  Trajectory trajectory;
  for (int i = 0; i < n; ++i) {
    const double t = t0 + i / rate;
    trajectory.push_back({t, uniformMotion(t, motion_t0)});
  }
  return trajectory;
}

TEST(EvalAssociation, InterpolatesPositionLinearlyAndRotationBySlerp) {
  const StampedPose a{10.0, yawPose(0.0, Eigen::Vector3d(0, 0, 0))};
  const StampedPose b{11.0, yawPose(1.0, Eigen::Vector3d(2, 4, -6))};
  const Pose mid = interpolatePose(a, b, 10.25);
  EXPECT_TRUE(mid.isApprox(yawPose(0.25, Eigen::Vector3d(0.5, 1.0, -1.5)), 1e-12, 1e-12));
  EXPECT_TRUE(interpolatePose(a, b, 9.0).isApprox(a.pose));   // clamped
  EXPECT_TRUE(interpolatePose(a, b, 12.0).isApprox(b.pose));  // clamped
}

TEST(EvalAssociation, TruthAtAnyRateIsInterpolatedAtTheEstimateStamps) {
  const double t0 = 1700000000.0;                             // absolute stamps, as recorded
  const Trajectory gt = sampled(t0, 400.0, 4001, t0);         // 10 s at 400 Hz (IMU rate)
  const Trajectory est = sampled(t0 + 0.0437, 10.0, 99, t0);  // 10 Hz, off the truth's grid
  const AssociatedPoses poses = associate(gt, est);
  ASSERT_EQ(poses.matched(), 99u);
  EXPECT_EQ(poses.outside_gt_span, 0u);
  EXPECT_EQ(poses.in_gt_gap, 0u);
  for (std::size_t i = 0; i < poses.matched(); ++i) {
    // Stamps near 1.7e9 s are exact to about 2.4e-7 s: 1e-6 m at 1 m/s.
    EXPECT_TRUE(poses.T_world_gt[i].isApprox(est[i].pose, 1e-6, 1e-6)) << i;
  }
}

TEST(EvalAssociation, CountsEstimatesOutsideTheTruthAndInItsGaps) {
  Trajectory gt = sampled(0.0, 10.0, 51, 0.0);           // 0 .. 5 s
  const Trajectory later = sampled(8.0, 10.0, 21, 0.0);  // 8 .. 10 s: a 3 s gap
  gt.insert(gt.end(), later.begin(), later.end());
  const Trajectory est = sampled(-1.0, 10.0, 121, 0.0);  // -1 .. 11 s
  const AssociatedPoses poses = associate(gt, est);
  // Outside: -1.0 .. -0.1 (10) and 10.1 .. 11.0 (10); in the gap: 5.1 .. 7.9 (29).
  EXPECT_EQ(poses.outside_gt_span, 20u);
  EXPECT_EQ(poses.in_gt_gap, 29u);
  EXPECT_EQ(poses.matched(), 121u - 20u - 29u);
  EXPECT_EQ(poses.est_poses, 121u);
}

TEST(EvalAssociation, NearestTruthWithinToleranceAtTheEnds) {
  const Trajectory gt = sampled(0.0, 10.0, 11, 0.0);  // 0 .. 1 s
  Trajectory est = {{-0.005, uniformMotion(0.0, 0.0)},
                    {0.5, uniformMotion(0.5, 0.0)},
                    {1.008, uniformMotion(1.0, 0.0)}};
  AssociationOptions options;
  options.max_time_difference = 0.01;
  const AssociatedPoses poses = associate(gt, est, options);
  ASSERT_EQ(poses.matched(), 3u);
  EXPECT_TRUE(poses.T_world_gt.front().isApprox(gt.front().pose));
  EXPECT_TRUE(poses.T_world_gt.back().isApprox(gt.back().pose));

  options.max_time_difference = 0.001;
  EXPECT_THROW(associate(gt, est, options), Error);  // only the middle pose is left
}

TEST(EvalAssociation, DifferentClocksAreAnErrorShowingBothSpans) {
  const Trajectory gt = sampled(1700000000.0, 10.0, 100, 1700000000.0);
  const Trajectory est = sampled(0.0, 10.0, 100, 0.0);  // relative stamps
  try {
    associate(gt, est);
    FAIL() << "expected storey::Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("only 0 estimated poses"), std::string::npos) << message;
    EXPECT_NE(message.find("1700000000.000000"), std::string::npos) << message;
    EXPECT_NE(message.find("t = 0.000000"), std::string::npos) << message;
  }
}

TEST(EvalAssociation, RejectsBadOptions) {
  AssociationOptions options;
  options.max_interpolation_gap = 0.0;
  EXPECT_THROW(options.validate(), Error);
  options = {};
  options.max_time_difference = -1.0;
  EXPECT_THROW(options.validate(), Error);
}

}  // namespace
}  // namespace storey::eval
