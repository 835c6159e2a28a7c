// Association on hand-built cases: a corridor's two parallel walls face each
// other (told apart by the side they are seen from); two parallel walls facing
// the same way closer than the gates are ambiguous; joint matching picks the
// wall whose normal agrees with the rotation the other planes imply.
#include <gtest/gtest.h>

#include "backend/association.h"

namespace storey::backend {
namespace {

DetectedPlane srp(const Eigen::Vector3d& n, double d, int points = 2000) {
  DetectedPlane p;
  p.plane = Plane(n, d);
  p.centroid = n.normalized() * d;  // the foot of the sensor on the plane
  p.points = points;
  p.covariance = Eigen::Vector3d(1e-6, 1e-6, 1e-5).asDiagonal();
  return p;
}

/// A landmark seen by `observations` keyframes (default: confirmed).
PlanePrediction predicted(int id, const Eigen::Vector3d& n, double d, int observations = 5) {
  return {id, n.normalized(), d, observations};
}

Eigen::Vector3d yawed(const Eigen::Vector3d& n, double deg) {
  return Eigen::AngleAxisd(deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()) * n;
}

TEST(Association, CorridorWallsFacingEachOtherAreToldApart) {
  // Corridor 2.2 m wide along x; the sensor in the middle, 0.6 m above the floor.
  const std::vector<PlanePrediction> map{
      predicted(0, {0, 1, 0}, 1.1), predicted(1, {0, -1, 0}, 1.1), predicted(2, {0, 0, -1}, 0.6)};
  // Observed with a 1 deg yaw error and 5 cm offset across the corridor.
  const std::vector<DetectedPlane> srps{srp({0, 0, -1}, 0.61), srp(yawed({0, 1, 0}, 1.0), 1.15),
                                        srp(yawed({0, -1, 0}, 1.0), 1.05)};
  const AssociationResult r = associate(srps, map, AssociationConfig{});
  ASSERT_EQ(r.srps.size(), 3u);
  EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kMatched);
  EXPECT_EQ(r.srps[0].landmark, 2);
  EXPECT_EQ(r.srps[1].outcome, AssociationOutcome::kMatched);
  EXPECT_EQ(r.srps[1].landmark, 0);
  EXPECT_EQ(r.srps[2].outcome, AssociationOutcome::kMatched);
  EXPECT_EQ(r.srps[2].landmark, 1);
  EXPECT_GE(r.gate_rejects[static_cast<std::size_t>(GateReject::kFacing)], 2);
}

TEST(Association, ParallelWallsCloserThanTheGatesAreAmbiguous) {
  // Two walls facing the same way, 0.25 m apart (a recess); the SRP lies between them.
  const std::vector<PlanePrediction> map{
      predicted(0, {1, 0, 0}, 2.0), predicted(1, {1, 0, 0}, 2.25), predicted(2, {0, 0, -1}, 0.6)};
  const std::vector<DetectedPlane> srps{srp({1, 0, 0}, 2.125), srp({0, 0, -1}, 0.6)};
  const AssociationResult r = associate(srps, map, AssociationConfig{});
  EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kAmbiguous);
  EXPECT_EQ(r.srps[0].candidates, 2);
  EXPECT_EQ(r.srps[1].outcome, AssociationOutcome::kMatched);
  EXPECT_EQ(r.srps[1].landmark, 2);
}

TEST(Association, ParallelWallsFartherApartThanTheGatesMatchTheRightOne) {
  const std::vector<PlanePrediction> map{predicted(0, {1, 0, 0}, 2.0),
                                         predicted(1, {1, 0, 0}, 2.7)};
  for (double d : {1.95, 2.05, 2.65, 2.75}) {
    const AssociationResult r = associate({srp({1, 0, 0}, d)}, map, AssociationConfig{});
    EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kMatched) << d;
    EXPECT_EQ(r.srps[0].landmark, d < 2.4 ? 0 : 1) << d;
  }
}

TEST(Association, JointMatchingUsesTheRotationOfTheOtherPlanes) {
  // Two walls facing +x at the same distance, their normals 4 deg apart in yaw
  // (within the 6 deg gate). Alone, an SRP half-way between them is ambiguous.
  const std::vector<PlanePrediction> map{
      predicted(0, {1, 0, 0}, 3.0), predicted(1, yawed({1, 0, 0}, 4.0), 3.0),
      predicted(2, {0, 1, 0}, 1.5), predicted(3, {0, 0, -1}, 0.6)};
  const DetectedPlane between = srp(yawed({1, 0, 0}, 2.0), 3.0);
  EXPECT_EQ(associate({between}, map, AssociationConfig{}).srps[0].outcome,
            AssociationOutcome::kAmbiguous);
  // With the orthogonal wall observed 2 deg yawed as well, one rotation of the
  // keyframe explains both only if the first wall is landmark 0.
  const std::vector<DetectedPlane> srps{between, srp(yawed({0, 1, 0}, 2.0), 1.5),
                                        srp({0, 0, -1}, 0.6)};
  const AssociationResult r = associate(srps, map, AssociationConfig{});
  EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kMatched);
  EXPECT_EQ(r.srps[0].landmark, 0);
  EXPECT_EQ(r.srps[1].landmark, 2);
  EXPECT_EQ(r.srps[2].landmark, 3);
}

TEST(Association, UnknownPlanesAreNewButNotNextToAKnownOne) {
  const std::vector<PlanePrediction> map{predicted(0, {1, 0, 0}, 2.0)};
  const AssociationResult r = associate(
      {srp({0, 1, 0}, 2.0), srp({1, 0, 0}, 2.35), srp({1, 0, 0}, 4.0)}, map, AssociationConfig{});
  EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kNewPlane);
  EXPECT_EQ(r.srps[1].outcome, AssociationOutcome::kNearExisting);
  EXPECT_EQ(r.srps[2].outcome, AssociationOutcome::kNewPlane);
}

TEST(Association, APlaneSeenOnceDoesNotKeepARealOneOut) {
  // building-b: a phantom level plane 0.3 m above a storey's floor, seen by one
  // keyframe, kept that floor out of the graph for the whole storey. Seen once
  // it blocks nothing; seen by two keyframes it is confirmed and does.
  const DetectedPlane floor = srp({0, 0, -1}, 0.62);
  for (int seen : {1, 2}) {
    const std::vector<PlanePrediction> map{predicted(0, {0, 0, -1}, 0.31, seen)};
    const AssociationResult r = associate({floor}, map, AssociationConfig{});
    EXPECT_EQ(r.srps[0].outcome,
              seen == 1 ? AssociationOutcome::kNewPlane : AssociationOutcome::kNearExisting)
        << seen;
  }
  // The rule is the configuration's.
  AssociationConfig strict;
  strict.confirmed_observations = 1;
  EXPECT_EQ(associate({floor}, {predicted(0, {0, 0, -1}, 0.31, 1)}, strict).srps[0].outcome,
            AssociationOutcome::kNearExisting);
}

TEST(Association, TiltIsKnownBetterThanYaw) {
  // A floor landmark 1.3 m under the sensor and a surface 4 deg off level (a
  // band across two levels, a ramp) seen at the same distance below: with the
  // tilt as uncertain as the yaw (20 mrad) it passes the uncertainty gate (a
  // candidate for the floor, and the floor is no longer matched for sure);
  // with the tilt of a gravity-aligned odometry (5 mrad) it does not. A wall seen with a 1 deg yaw
  // error still matches: the yaw keeps its 20 mrad.
  const std::vector<PlanePrediction> map{predicted(0, {0, 0, -1}, 1.3),
                                         predicted(1, {0, 1, 0}, 1.1)};
  const Eigen::Vector3d slanted =
      Eigen::AngleAxisd(4.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()) * Eigen::Vector3d(0, 0, -1);
  const std::vector<DetectedPlane> srps{srp(slanted, 1.3), srp(yawed({0, 1, 0}, 1.0), 1.1)};
  AssociationConfig tilt_as_yaw;
  tilt_as_yaw.pose_sigma_tilt = tilt_as_yaw.pose_sigma_rotation;
  AssociationConfig gravity;
  gravity.pose_sigma_tilt = 0.005;
  const AssociationResult loose = associate(srps, map, tilt_as_yaw, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(loose.srps[0].candidates, 1);
  EXPECT_NE(loose.srps[0].outcome, AssociationOutcome::kNewPlane);
  const AssociationResult r = associate(srps, map, gravity, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(r.srps[0].candidates, 0);
  EXPECT_NE(r.srps[0].outcome, AssociationOutcome::kMatched);
  EXPECT_EQ(r.srps[1].outcome, AssociationOutcome::kMatched);
  EXPECT_EQ(r.srps[1].landmark, 1);
  // Up is the keyframe's: the same scene seen by a keyframe rolled by 90 deg
  // (up along its y) gives the same decisions.
  const Eigen::Matrix3d R_kf_rolled =
      Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  std::vector<PlanePrediction> map_rolled = map;
  for (PlanePrediction& p : map_rolled) p.n_kf = R_kf_rolled * p.n_kf;
  std::vector<DetectedPlane> srps_rolled = srps;
  for (DetectedPlane& p : srps_rolled)
    p.plane = Plane(R_kf_rolled * p.plane.normal(), p.plane.distance());
  const AssociationResult rolled =
      associate(srps_rolled, map_rolled, gravity, R_kf_rolled * Eigen::Vector3d::UnitZ());
  EXPECT_EQ(rolled.srps[0].candidates, 0);
  EXPECT_EQ(rolled.srps[1].outcome, AssociationOutcome::kMatched);
}

TEST(Association, ATrackedLandmarkIsNotMatchedToAParallelFaceBeside) {
  // A floor landmark the graph predicts 1.30 m under the sensor; an SRP 6 cm
  // lower (a slab's step, a landing beside a flight): within every gate of the
  // prediction, so without tracking it is matched.
  const Eigen::Vector3d down(0, 0, -1);
  const DetectedPlane lower = srp(down, 1.36);
  const PlanePrediction untracked = predicted(0, down, 1.30);
  AssociationResult r = associate({lower}, {untracked}, AssociationConfig{});
  EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kMatched);
  // Tracked: its newest view, moved here by the odometry, is also at 1.30 m, so
  // the SRP is another surface: not this landmark, and free to be a new plane.
  PlanePrediction tracked = untracked;
  tracked.tracked = true;
  tracked.n_track_kf = down;
  tracked.d_track_kf = 1.30;
  r = associate({lower}, {tracked}, AssociationConfig{});
  EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kNewPlane);
  EXPECT_EQ(r.gate_rejects[static_cast<std::size_t>(GateReject::kFaceChange)], 1);
  EXPECT_STREQ(toString(GateReject::kFaceChange), "not_the_tracked_face");
  // The graph's prediction is 5 cm off (drift) but the newest view agrees with
  // the SRP: matched, as the odometry knows where the surface went.
  tracked.d_track_kf = 1.35;
  r = associate({lower}, {tracked}, AssociationConfig{});
  EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kMatched);
  EXPECT_EQ(r.srps[0].landmark, 0);
  // The gate is the configuration's.
  tracked.d_track_kf = 1.30;
  AssociationConfig wide;
  wide.track_gate = 0.08;
  r = associate({lower}, {tracked}, wide);
  EXPECT_EQ(r.srps[0].outcome, AssociationOutcome::kMatched);
}

}  // namespace
}  // namespace storey::backend
