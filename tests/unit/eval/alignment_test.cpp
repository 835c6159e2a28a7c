// Alignment and ATE against transforms and perturbations with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "eval/alignment.h"
#include "eval/ate.h"
#include "unit/eval/eval_fixtures.h"

namespace storey::eval {
namespace {

using test::eval::wigglyWalk;
using test::eval::yawPose;

/// Associated poses with the truth `gt` and the estimate T_est_gt * gt.
AssociatedPoses transformed(const Trajectory& gt, const Pose& T_est_gt) {
  AssociatedPoses poses;
  for (const StampedPose& s : gt) {
    poses.times.push_back(s.time);
    poses.T_world_gt.push_back(s.pose);
    poses.T_world_est.push_back(T_est_gt * s.pose);
  }
  poses.est_poses = gt.size();
  return poses;
}

Positions positionsOf(const std::vector<Pose>& poses) {
  Positions p;
  for (const Pose& T : poses) p.push_back(T.translation());
  return p;
}

TEST(EvalAlignment, Se3RecoversAKnownTransformExactly) {
  const Trajectory gt = wigglyWalk(200);
  const Pose T_est_gt(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())),
      Eigen::Vector3d(5.0, -3.0, 1.5));
  const AssociatedPoses poses = transformed(gt, T_est_gt);
  const Pose T_gt_est = alignSe3(positionsOf(poses.T_world_est), positionsOf(poses.T_world_gt));
  EXPECT_TRUE(T_gt_est.isApprox(T_est_gt.inverse(), 1e-9, 1e-9));

  const AteResult aligned = absoluteTrajectoryError(poses, Alignment::kSe3);
  EXPECT_EQ(aligned.translation.count, 200u);
  EXPECT_LT(aligned.translation.rmse, 1e-9);
  EXPECT_LT(aligned.translation.max, 1e-9);
  EXPECT_LT(aligned.rotation.max, 1e-9);
  // Without alignment the same estimate is far off: the fixture tests something.
  EXPECT_GT(absoluteTrajectoryError(poses, Alignment::kNone).translation.rmse, 1.0);
}

TEST(EvalAlignment, YawTranslationRecoversAYawOffsetButNotARoll) {
  const Trajectory gt = wigglyWalk(200);
  const Pose T_est_gt = yawPose(-2.5, Eigen::Vector3d(1.0, 2.0, -0.3));
  const AssociatedPoses poses = transformed(gt, T_est_gt);
  const AteResult yaw = absoluteTrajectoryError(poses, Alignment::kYawTranslation);
  EXPECT_TRUE(yaw.T_gt_est.isApprox(T_est_gt.inverse(), 1e-9, 1e-9));
  EXPECT_LT(yaw.translation.rmse, 1e-9);

  const Pose T_rolled(Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX())),
                      Eigen::Vector3d::Zero());
  const AssociatedPoses rolled = transformed(gt, T_rolled);
  EXPECT_GT(absoluteTrajectoryError(rolled, Alignment::kYawTranslation).translation.rmse, 0.05);
  EXPECT_LT(absoluteTrajectoryError(rolled, Alignment::kSe3).translation.rmse, 1e-9);
}

/// The gravity parts of the error: a world yaw and a sideways shift give no
/// tilt and no height error; the same truth with every pose turned by 5 mrad
/// about a horizontal world axis and lifted by 2 cm gives exactly that tilt
/// and height.
TEST(EvalAte, TiltAndHeightErrorsSeeOnlyWhatGravitySees) {
  const Trajectory gt = wigglyWalk(100);
  const AteResult yawed = absoluteTrajectoryError(
      transformed(gt, yawPose(0.4, Eigen::Vector3d(0.3, -0.2, 0.0))), Alignment::kNone);
  EXPECT_GT(yawed.rotation.max, 0.39);
  EXPECT_LT(yawed.tilt.max, 1e-12);
  EXPECT_LT(yawed.vertical.max, 1e-12);

  AssociatedPoses tilted;
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.005, Eigen::Vector3d(1, 1, 0).normalized()));
  for (const StampedPose& s : gt) {
    tilted.times.push_back(s.time);
    tilted.T_world_gt.push_back(s.pose);
    tilted.T_world_est.push_back(
        Pose(turn * s.pose.rotation(), s.pose.translation() + Eigen::Vector3d(0, 0, 0.02)));
  }
  tilted.est_poses = gt.size();
  const AteResult a = absoluteTrajectoryError(tilted, Alignment::kNone);
  EXPECT_EQ(a.tilt.count, 100u);
  EXPECT_NEAR(a.tilt.median, 0.005, 1e-9);
  EXPECT_NEAR(a.tilt.max, 0.005, 1e-9);
  EXPECT_NEAR(a.vertical.max, 0.02, 1e-12);
}

TEST(EvalAlignment, NeedsTwoPairsOfTheSameCount) {
  EXPECT_THROW(alignSe3({Eigen::Vector3d::Zero()}, {Eigen::Vector3d::Zero()}), Error);
  EXPECT_THROW(
      alignSe3({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()}, {Eigen::Vector3d::Zero()}),
      Error);
}

// Truth: the corners of a unit square; estimate: rotated 90 deg about z and
// lifted 0.5 m. By hand, the unaligned errors are |R p + t - p| = 0.5, 1.5,
// sqrt(4.25), 1.5: RMSE sqrt(9/4) = 1.5, and every rotation error is 90 deg.
TEST(EvalAte, KnownRotationAndTranslationOffsetGivesTheHandComputedAte) {
  Trajectory gt;
  const Eigen::Vector3d corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (int i = 0; i < 4; ++i)
    gt.push_back({1.0 + i, Pose(Eigen::Quaterniond::Identity(), corners[i])});
  const AssociatedPoses poses = transformed(gt, yawPose(M_PI / 2, Eigen::Vector3d(0, 0, 0.5)));

  const AteResult none = absoluteTrajectoryError(poses, Alignment::kNone);
  EXPECT_NEAR(none.translation.rmse, 1.5, 1e-12);
  EXPECT_NEAR(none.translation.mean, (0.5 + 1.5 + std::sqrt(4.25) + 1.5) / 4.0, 1e-12);
  EXPECT_NEAR(none.translation.max, std::sqrt(4.25), 1e-12);
  EXPECT_NEAR(none.translation.median, 1.5, 1e-12);
  EXPECT_NEAR(none.rotation.rmse, M_PI / 2, 1e-12);
  EXPECT_LT(absoluteTrajectoryError(poses, Alignment::kSe3).translation.rmse, 1e-12);
  EXPECT_LT(absoluteTrajectoryError(poses, Alignment::kYawTranslation).translation.rmse, 1e-12);
}

// Truth: a square's corners (+-1, +-1, 0); estimate: the same with z offsets
// +0.1, -0.1, +0.1, -0.1 (a saddle: no mean, no tilt). No rigid motion removes
// them, so aligned or not every error is 0.1 m.
TEST(EvalAte, PerturbedTrajectoryGivesTheHandComputedAte) {
  AssociatedPoses poses;
  const Eigen::Vector3d corners[4] = {{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}};
  for (int i = 0; i < 4; ++i) {
    poses.times.push_back(i);
    poses.T_world_gt.push_back(Pose(Eigen::Quaterniond::Identity(), corners[i]));
    poses.T_world_est.push_back(Pose(Eigen::Quaterniond::Identity(),
                                     corners[i] + Eigen::Vector3d(0, 0, i % 2 ? -0.1 : 0.1)));
  }
  for (Alignment a : {Alignment::kNone, Alignment::kSe3, Alignment::kYawTranslation}) {
    const AteResult ate = absoluteTrajectoryError(poses, a);
    EXPECT_NEAR(ate.translation.rmse, 0.1, 1e-12) << toString(a);
    EXPECT_NEAR(ate.translation.mean, 0.1, 1e-12) << toString(a);
    EXPECT_NEAR(ate.translation.max, 0.1, 1e-12) << toString(a);
    EXPECT_TRUE(ate.T_gt_est.isApprox(Pose::identity(), 1e-12, 1e-12)) << toString(a);
  }
}

}  // namespace
}  // namespace storey::eval
