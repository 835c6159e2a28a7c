// The keyframe graph on a synthetic corridor walk: a drifting odometry
// (height, pitch, yaw) is pulled back onto the truth by plane observations of
// the floor and walls; an injected wrong association (a wall 0.5 m off) is
// down-weighted by the robust loss, leaves the poses accurate and is the one
// observation reported as wrong.
#include <gtest/gtest.h>

#include <random>

#include "backend/plane_graph.h"

namespace storey::backend {
namespace {

struct Fixture {
  std::vector<Pose> truth, odometry;
  std::vector<PlaneLandmark> planes{{{0, 0, -1}, 0.6},   // floor z = -0.6
                                    {{0, 1, 0}, 1.1},    // left wall y = 1.1
                                    {{0, -1, 0}, 1.1},   // right wall y = -1.1
                                    {{1, 0, 0}, 40.0}};  // end wall x = 40
  Fixture() {
    const int n = 30;
    for (int i = 0; i < n; ++i) {
      const double yaw = 0.05 * std::sin(i / 4.0);
      truth.emplace_back(Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())),
                         Eigen::Vector3d(1.0 * i, 0.3 * std::sin(i / 5.0), 0.0));
    }
    // Odometry: the true steps with a bias per step (z 1 cm, pitch 0.1 deg, yaw 0.2 deg).
    const Pose bias(Eigen::Quaterniond(Eigen::AngleAxisd(0.0035, Eigen::Vector3d::UnitZ()) *
                                       Eigen::AngleAxisd(0.0017, Eigen::Vector3d::UnitY())),
                    Eigen::Vector3d(0.0, 0.0, 0.01));
    odometry.push_back(truth[0]);
    for (int i = 1; i < n; ++i)
      odometry.push_back(odometry.back() * (truth[i - 1].inverse() * truth[i]) * bias);
  }
  /// Plane j as the keyframe i sees it (oriented like the landmark).
  std::pair<Eigen::Vector3d, double> observe(int i, int j) const {
    const Pose& T = truth[static_cast<std::size_t>(i)];
    const PlaneLandmark& l = planes[static_cast<std::size_t>(j)];
    return {T.rotation().conjugate() * l.n_world, l.d_world - l.n_world.dot(T.translation())};
  }
};

double maxTranslationError(const PlaneGraph& g, const Fixture& f) {
  double e = 0;
  for (int i = 0; i < g.keyframes(); ++i)
    e = std::max(
        e, (g.keyframePose(i).translation() - f.truth[static_cast<std::size_t>(i)].translation())
               .norm());
  return e;
}

double maxHeightError(const PlaneGraph& g, const Fixture& f) {
  double e = 0;
  for (int i = 0; i < g.keyframes(); ++i)
    e = std::max(e, std::abs(g.keyframePose(i).translation().z() -
                             f.truth[static_cast<std::size_t>(i)].translation().z()));
  return e;
}

double maxRotationError(const PlaneGraph& g, const Fixture& f) {
  double e = 0;
  for (int i = 0; i < g.keyframes(); ++i)
    e = std::max(e, (f.truth[static_cast<std::size_t>(i)].inverse() * g.keyframePose(i)).angle());
  return e;
}

/// Builds the graph from the fixture; `wrong_at` >= 0 adds a wrong observation there.
int build(PlaneGraph& g, const Fixture& f, int wrong_at) {
  const Eigen::Matrix3d cov = Eigen::Vector3d(1e-6, 1e-6, 1e-5).asDiagonal();
  Eigen::Matrix<double, 6, 1> info;
  info << 1e4, 1e4, 1e4, 1e5, 1e5, 1e5;  // 1 cm, 0.18 deg per step
  for (const PlaneLandmark& l : f.planes) g.addLandmark(l);
  int wrong = -1;
  for (std::size_t i = 0; i < f.truth.size(); ++i) {
    const int k = g.addKeyframe(f.odometry[i]);
    if (k > 0)
      g.addRelativePose(k - 1, k, f.odometry[i - 1].inverse() * f.odometry[i], info.asDiagonal());
    for (int j = 0; j < 4; ++j) {
      const auto [n, d] = f.observe(k, j);
      g.addObservation(k, j, n, d, cov);
    }
    if (k == wrong_at) {
      // The left wall's parallel neighbour 0.5 m farther, matched to the left wall.
      const auto [n, d] = f.observe(k, 1);
      wrong = g.addObservation(k, 1, n, d + 0.5, cov);
    }
  }
  return wrong;
}

TEST(PlaneGraph, PlanesRemoveOdometryDrift) {
  const Fixture f;
  PlaneGraph g{GraphConfig{}};
  build(g, f, -1);
  // Fixture property: the odometry alone drifts by decimetres.
  double drift = 0;
  for (std::size_t i = 0; i < f.truth.size(); ++i)
    drift = std::max(drift, (f.odometry[i].translation() - f.truth[i].translation()).norm());
  ASSERT_GT(drift, 0.2);
  const GraphSolveStats s = g.optimise(0, 50);
  EXPECT_TRUE(s.full);
  EXPECT_LT(s.final_cost, s.initial_cost);
  EXPECT_LT(maxTranslationError(g, f), 0.01);
  EXPECT_LT(maxRotationError(g, f), 0.002);
  for (int o = 0; o < g.observations(); ++o) EXPECT_LT(g.observationChi2(o), 4.0);
  // The landmarks stay where they are (the first keyframe is fixed at the truth).
  EXPECT_NEAR(g.landmark(0).d_world, 0.6, 1e-3);
  EXPECT_GT(g.landmark(0).n_world.dot(Eigen::Vector3d(0, 0, -1)), std::cos(1e-3));
}

TEST(PlaneGraph, InjectedWrongAssociationIsRobustifiedAndReported) {
  const Fixture f;
  PlaneGraph g{GraphConfig{}};
  const int wrong = build(g, f, 15);
  g.optimise(0, 50);
  EXPECT_LT(maxTranslationError(g, f), 0.02);
  EXPECT_LT(maxRotationError(g, f), 0.002);
  const double outlier_chi2 = GraphConfig{}.outlier_chi2;
  EXPECT_GT(g.observationChi2(wrong), outlier_chi2);
  for (int o = 0; o < g.observations(); ++o)
    if (o != wrong) {
      EXPECT_LT(g.observationChi2(o), outlier_chi2) << o;
    }
}

/// Largest difference of the keyframe positions of two graphs.
double maxPositionDifference(const PlaneGraph& a, const PlaneGraph& b) {
  double e = 0;
  for (int i = 0; i < a.keyframes(); ++i)
    e = std::max(e, (a.keyframePose(i).translation() - b.keyframePose(i).translation()).norm());
  return e;
}

/// The robust loss bounds a wrong association's pull but does not remove it;
/// an excluded observation is out of every later solve: the graph then
/// solves to what it would be had the observation never been made.
TEST(PlaneGraph, ExcludedObservationNoLongerPulls) {
  const Fixture f;
  PlaneGraph clean{GraphConfig{}}, g{GraphConfig{}};
  build(clean, f, -1);
  const int wrong = build(g, f, 15);
  clean.optimise(0, 50);
  const GraphSolveStats with = g.optimise(0, 50);
  // Fixture property: under the loss the wrong observation still moves the
  // poses (by ~0.08 mm; the solver's tolerance leaves ~1e-6 m).
  const double pulled = maxPositionDifference(g, clean);
  ASSERT_GT(pulled, 1e-5);
  EXPECT_FALSE(g.observationExcluded(wrong));
  g.excludeObservation(wrong);
  EXPECT_TRUE(g.observationExcluded(wrong));
  const GraphSolveStats without = g.optimise(0, 50);
  EXPECT_EQ(without.residual_blocks, with.residual_blocks - 1);
  EXPECT_LT(maxPositionDifference(g, clean), 0.05 * pulled);
  // Still evaluated (reported), and still as wrong as it was.
  EXPECT_GT(g.observationChi2(wrong), GraphConfig{}.outlier_chi2);
}

TEST(PlaneGraph, WindowedSolvesThenAFullSolveConverge) {
  const Fixture f;
  PlaneGraph g{GraphConfig{}};
  build(g, f, -1);
  const GraphSolveStats w = g.optimise(10, 10);
  EXPECT_FALSE(w.full);
  EXPECT_EQ(w.free_keyframes, 10);
  // Keyframes outside the window have not moved.
  EXPECT_TRUE(g.keyframePose(5).isApprox(f.odometry[5], 1e-12, 1e-12));
  g.optimise(0, 50);
  EXPECT_LT(maxTranslationError(g, f), 0.01);
}

/// A windowed solve keeps, per free plane, only the newest
/// window_held_observations of the observations by held keyframes (every one
/// by the window's keyframes); a whole-graph solve keeps all.
TEST(PlaneGraph, WindowedSolveKeepsTheNewestHeldObservations) {
  const Fixture f;  // 30 keyframes, each observing the 4 planes
  GraphConfig all;
  all.window_held_observations = 0;
  GraphConfig capped;
  capped.window_held_observations = 5;
  PlaneGraph g_all{all}, g_capped{capped};
  build(g_all, f, -1);
  build(g_capped, f, -1);
  const GraphSolveStats w_all = g_all.optimise(10, 10);
  const GraphSolveStats w_capped = g_capped.optimise(10, 10);
  EXPECT_EQ(w_all.held_observations_left_out, 0);
  // 20 held keyframes see each of the 4 planes; 5 of each kept.
  EXPECT_EQ(w_capped.held_observations_left_out, 4 * (20 - 5));
  EXPECT_EQ(w_capped.residual_blocks, w_all.residual_blocks - 4 * (20 - 5));
  EXPECT_EQ(w_capped.free_keyframes, 10);
  EXPECT_EQ(w_capped.free_planes, 4);
  const GraphSolveStats full = g_capped.optimise(0, 50);
  EXPECT_EQ(full.held_observations_left_out, 0);
  EXPECT_LT(maxTranslationError(g_capped, f), 0.01);
}

/// Largest tilt (angle between the estimated and the true up direction in the
/// keyframe frame) over the keyframes.
double maxTiltError(const PlaneGraph& g, const Fixture& f) {
  double e = 0;
  for (int i = 0; i < g.keyframes(); ++i) {
    const Eigen::Vector3d up_estimate =
        g.keyframePose(i).rotation().conjugate() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d up_true =
        f.truth[static_cast<std::size_t>(i)].rotation().conjugate() * Eigen::Vector3d::UnitZ();
    e = std::max(e, std::acos(std::min(1.0, up_estimate.dot(up_true))));
  }
  return e;
}

/// A run of keyframes whose floor fits are all pitched by 8 mrad (a ramp or a
/// biased fit matched to the floor: correlated errors, not noise) tilts those
/// keyframes when only the odometry edges hold them; the tilt prior, from an
/// odometry whose gravity is right, keeps them level.
TEST(PlaneGraph, TiltPriorHoldsKeyframesAgainstCorrelatedPlaneErrors) {
  const Fixture f;
  auto solve = [&](double tilt_prior_sigma) {
    GraphConfig config;
    config.tilt_prior_sigma = tilt_prior_sigma;
    PlaneGraph g{config};
    const Eigen::Matrix3d cov = Eigen::Vector3d(1e-5, 1e-5, 1e-4).asDiagonal();
    Eigen::Matrix<double, 6, 1> info;
    info << 1e4, 1e4, 1e4, 2.5e5, 2.5e5, 2.5e5;  // 1 cm, 2 mrad per step
    for (const PlaneLandmark& l : f.planes) g.addLandmark(l);
    const Eigen::Quaterniond pitch(Eigen::AngleAxisd(0.008, Eigen::Vector3d::UnitY()));
    for (std::size_t i = 0; i < f.truth.size(); ++i) {
      // Odometry with the truth's relative poses and attitude (its gravity is right).
      const int k = g.addKeyframe(f.truth[i]);
      g.setTiltReference(k, f.truth[i].rotation());
      if (k > 0)
        g.addRelativePose(k - 1, k, f.truth[i - 1].inverse() * f.truth[i], info.asDiagonal());
      for (int j = 0; j < 4; ++j) {
        auto [n, d] = f.observe(k, j);
        if (j == 0 && k >= 10 && k < 20) n = pitch * n;
        g.addObservation(k, j, n, d, cov);
      }
    }
    g.optimise(0, 50);
    return maxTiltError(g, f);
  };
  const double without = solve(0.0);
  const double with = solve(0.002);
  EXPECT_GT(without, 0.002);
  EXPECT_LT(with, 0.5 * without);
  // Off by default (docs/method/backend.md says why).
  EXPECT_EQ(GraphConfig{}.tilt_prior_sigma, 0.0);
}

/// An odometry whose positions are right but whose attitude is pitched by
/// 3 mrad (a LiDAR-inertial odometry's attitude and position errors are not
/// one error): the graph levels the keyframes with the walls, and the
/// body-frame edges then turn every step along the corridor by 3 mrad (7.5
/// cm of height over the 29 m); the heading-frame edges keep the odometry's
/// heights.
TEST(PlaneGraph, HeadingFrameEdgesKeepTheOdometrysHeightsWhenTheGraphLevelsIt) {
  const Fixture f;
  const Eigen::Quaterniond pitch(Eigen::AngleAxisd(0.003, Eigen::Vector3d::UnitY()));
  auto solve = [&](bool heading) {
    GraphConfig config;
    config.heading_frame_edges = heading;
    PlaneGraph g{config};
    const Eigen::Matrix3d cov = Eigen::Vector3d(1e-6, 1e-6, 1e-5).asDiagonal();
    Eigen::Matrix<double, 6, 1> info;
    info << 1e4, 1e4, 1e4, 1e6, 1e6, 1e6;  // 1 cm, 1 mrad per step
    for (const PlaneLandmark& l : f.planes) g.addLandmark(l);
    std::vector<Pose> odometry;
    for (const Pose& T : f.truth) odometry.emplace_back(T.rotation() * pitch, T.translation());
    for (std::size_t i = 0; i < f.truth.size(); ++i) {
      const int k = g.addKeyframe(odometry[i]);
      g.setTiltReference(k, odometry[i].rotation());
      if (k > 0)
        g.addRelativePose(k - 1, k, odometry[i - 1].inverse() * odometry[i], info.asDiagonal());
      for (int j = 1; j < 4; ++j) {  // the walls only: no floor holds the height
        const auto [n, d] = f.observe(k, j);
        g.addObservation(k, j, n, d, cov);
      }
    }
    g.optimise(0, 50);
    double tilt = 0.0, height = 0.0;
    for (int i = 0; i < g.keyframes(); ++i) {
      const Pose T = g.keyframePose(i);
      const Pose& truth = f.truth[static_cast<std::size_t>(i)];
      tilt = std::max(tilt, (T.rotation() * Eigen::Vector3d::UnitZ())
                                .cross(truth.rotation() * Eigen::Vector3d::UnitZ())
                                .norm());
      height = std::max(height, std::abs(T.translation().z() - truth.translation().z()));
    }
    return std::make_pair(tilt, height);
  };
  const auto [body_tilt, body_height] = solve(false);
  const auto [heading_tilt, heading_height] = solve(true);
  EXPECT_LT(body_tilt, 0.001);  // the walls level the keyframes in both
  EXPECT_LT(heading_tilt, 0.001);
  EXPECT_GT(body_height, 0.05);
  EXPECT_LT(heading_height, 1e-4);
  EXPECT_FALSE(GraphConfig{}.heading_frame_edges);  // off by default (docs/method/backend.md)
}

/// Solves the fixture's walk with height spans (5 keyframes, 2 mm; 0
/// keyframes: none) from the odometry `T_odom_kf` (also the start), the
/// floor's view at keyframe k `floor_bias_per_keyframe * k` nearer; returns
/// the largest height error.
double solveWithSpans(const Fixture& f, int span, bool keyframe_frame,
                      const std::vector<Pose>& T_odom_kf, double floor_bias_per_keyframe) {
  GraphConfig config;
  config.height_span_keyframes = span;
  config.height_span_sigma = 0.002;
  config.height_span_keyframe_frame = keyframe_frame;
  PlaneGraph g{config};
  const Eigen::Matrix3d cov = Eigen::Vector3d(1e-6, 1e-6, 1e-5).asDiagonal();
  Eigen::Matrix<double, 6, 1> info;
  info << 1e4, 1e4, 1e4, 1e6, 1e6, 1e6;  // 1 cm, 1 mrad per step
  for (const PlaneLandmark& l : f.planes) g.addLandmark(l);
  for (std::size_t i = 0; i < T_odom_kf.size(); ++i) {
    const int k = g.addKeyframe(T_odom_kf[i]);
    if (k > 0)
      g.addRelativePose(k - 1, k, T_odom_kf[i - 1].inverse() * T_odom_kf[i], info.asDiagonal());
    if (span > 0 && k >= span) {
      const Pose& T_odom_a = T_odom_kf[i - static_cast<std::size_t>(span)];
      g.addHeightDifference(k - span, k, T_odom_kf[i].translation() - T_odom_a.translation(),
                            T_odom_a.rotation(), config.height_span_sigma);
    }
    for (int j = 0; j < 4; ++j) {
      auto [n, d] = f.observe(k, j);
      if (j == 0) d -= floor_bias_per_keyframe * k;
      g.addObservation(k, j, n, d, cov);
    }
  }
  g.optimise(0, 50);
  return maxHeightError(g, f);
}

/// A pull spread over many views: the odometry is exact, and the floor's
/// views are biased by 1.5 mm more at every keyframe (as a run of views
/// each a little off, none far enough to be rejected), so each view
/// alone is within its uncertainty but together they ask the walk to sink
/// 4.4 cm over 30 keyframes. The edges (1 cm a step, a random walk over
/// the chain) let it; height spans (the odometry's height difference to
/// the keyframe five before, 2 mm) keep the odometry's heights.
TEST(PlaneGraph, HeightSpansKeepTheOdometrysHeightsAgainstASpreadPull) {
  const Fixture f;
  const double none = solveWithSpans(f, 0, false, f.truth, 0.0015);
  EXPECT_GT(none, 0.02);
  EXPECT_LT(solveWithSpans(f, 5, false, f.truth, 0.0015), 0.01);
  // In the older keyframe's frame a uniform sink along a straight walk is a
  // pitch of every keyframe, which only the floor's normal resists: the
  // spans hold half of it.
  EXPECT_LT(solveWithSpans(f, 5, true, f.truth, 0.0015), 0.6 * none);
  EXPECT_EQ(GraphConfig{}.height_span_keyframes, 0);  // off by default (docs/method/backend.md)
}

/// The odometry's map frame tilted by 4 mrad about the walk's normal (as an
/// odometry whose rigid map drifted from gravity, levelled once for the log):
/// its heights climb 12 cm along the 30 m walk while every view of the floor
/// is true. Spans in the odometry's levelled map frame keep that climb; in
/// the older keyframe's frame, turned by the graph's attitudes (which the
/// floor levels), they keep only the odometry's own motion (both start
/// from the odometry's poses: 0.116 against 0.009 m).
TEST(PlaneGraph, KeyframeFrameSpansFollowTheGraphsLevellingNotTheOdometrys) {
  const Fixture f;
  const Eigen::Quaterniond q_tilt(Eigen::AngleAxisd(-0.004, Eigen::Vector3d::UnitY()));
  std::vector<Pose> T_odom_kf;  // the true walk in a tilted frame
  for (const Pose& T : f.truth)
    T_odom_kf.emplace_back(q_tilt * T.rotation(), q_tilt * T.translation());
  EXPECT_GT(solveWithSpans(f, 5, false, T_odom_kf, 0.0), 0.03);
  EXPECT_LT(solveWithSpans(f, 5, true, T_odom_kf, 0.0), 0.015);
  EXPECT_FALSE(GraphConfig{}.height_span_keyframe_frame);
}

/// level: one band through parts of several treads (their fit RMS fills the
/// RANSAC band). Each is a new landmark seen once. If such a landmark got the
/// level prior, its one observation would say "this keyframe is tilted by the
/// fit's slope", and a run of them tilts the keyframes that see no floor
/// (and through the odometry edges, drops or raises the path). With a
/// tolerance of 1 deg they get no prior (docs/method/backend.md: why the
/// default is still 5 deg).
TEST(PlaneGraph, SurfacesTiltedBeyondTheToleranceGetNoLevelPrior) {
  const Fixture f;
  auto solve = [&](const GraphConfig& config) {
    PlaneGraph g{config};
    const Eigen::Matrix3d cov = Eigen::Vector3d(1e-5, 1e-5, 1e-4).asDiagonal();
    Eigen::Matrix<double, 6, 1> info;
    info << 1e4, 1e4, 1e4, 2.5e5, 2.5e5, 2.5e5;  // 1 cm, 2 mrad per step
    for (const PlaneLandmark& l : f.planes) g.addLandmark(l);
    for (std::size_t i = 0; i < f.truth.size(); ++i) {
      const int k = g.addKeyframe(f.truth[i]);
      if (k > 0)
        g.addRelativePose(k - 1, k, f.truth[i - 1].inverse() * f.truth[i], info.asDiagonal());
      // Keyframes 10-19 see the walls but not the floor, and one tread band
      // each, pitched by 3 deg (its landmark made from that one observation).
      for (int j = 0; j < 4; ++j) {
        if (j == 0 && k >= 10 && k < 20) continue;
        const auto [n, d] = f.observe(k, j);
        g.addObservation(k, j, n, d, cov);
      }
      if (k >= 10 && k < 20) {
        const Eigen::Vector3d n_world =
            Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()) *
            Eigen::Vector3d::UnitZ();
        const double d_world = 0.4 + n_world.dot(f.truth[i].translation());
        const int plane = g.addLandmark({n_world, d_world});
        const Pose& T = f.truth[i];
        g.addObservation(k, plane, T.rotation().conjugate() * n_world,
                         d_world - n_world.dot(T.translation()), cov);
      }
    }
    g.optimise(0, 50);
    return maxTiltError(g, f);
  };
  GraphConfig five_degrees, one_degree;
  five_degrees.level_tolerance_deg = 5.0;
  one_degree.level_tolerance_deg = 1.0;
  const double with_prior = solve(five_degrees);
  const double without_prior = solve(one_degree);
  EXPECT_GT(with_prior, 0.005);    // the bands' slope pulls the keyframes
  EXPECT_LT(without_prior, 1e-6);  // no prior: a band seen once constrains nothing
}

}  // namespace
}  // namespace storey::backend
