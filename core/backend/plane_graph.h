#pragma once
/// The keyframe factor graph of the back end, solved with Ceres: keyframe
/// poses, oriented plane landmarks (unit normal on the sphere + distance),
/// relative-pose factors from the odometry, plane-observation factors under a
/// Cauchy loss, level/plumb priors on floors and walls. The first keyframe is
/// held fixed (gauge). Solves either the newest keyframes (older ones held
/// fixed) or the whole graph, warm-started from the current estimate.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "backend/backend_config.h"
#include "types/pose.h"

namespace storey::backend {

struct PlaneLandmark {
  Eigen::Vector3d n_world = Eigen::Vector3d::UnitZ();  ///< unit; observers on the side opposite n
  double d_world = 0.0;                                ///< n . x = d [m], any sign
};

struct GraphSolveStats {
  bool full = false;  ///< the whole graph (else the newest keyframes only)
  int iterations = 0;
  int free_keyframes = 0, free_planes = 0, residual_blocks = 0;
  /// Observations by held keyframes left out (GraphConfig::window_held_observations).
  int held_observations_left_out = 0;
  double initial_cost = 0.0, final_cost = 0.0;
  double ms = 0.0;  ///< wall time of problem set-up and solve [ms]
};

class PlaneGraph {
 public:
  explicit PlaneGraph(const GraphConfig& config);
  ~PlaneGraph();
  PlaneGraph(const PlaneGraph&) = delete;
  PlaneGraph& operator=(const PlaneGraph&) = delete;

  /// Adds a keyframe at its initial estimate; returns its index (the first is fixed).
  int addKeyframe(const Pose& T_world_kf);
  /// The attitude the first keyframe's roll/pitch prior holds it to (at first
  /// its initial estimate's); no effect when first_tilt_sigma is 0 or there
  /// is no keyframe.
  void setFirstKeyframeAttitude(const Eigen::Quaterniond& q_world_kf);
  /// The odometry's own attitude of keyframe `kf` in its map frame: while the
  /// keyframe is free, a tilt prior (GraphConfig::tilt_prior_sigma,
  /// tilt_prior.h) holds its roll and pitch to q_world_odom R_odom_kf.
  void setTiltReference(int kf, const Eigen::Quaterniond& q_odom_kf);
  /// The odometry's latest levelling of its map frame (used by the next solves).
  void setOdometryLevelling(const Eigen::Quaterniond& q_world_odom);
  /// Odometry constraint T_a_b with its 6x6 information (translation, rotation; frame a).
  void addRelativePose(int a, int b, const Pose& T_a_b,
                       const Eigen::Matrix<double, 6, 6>& information);
  /// The odometry's height difference between keyframes a < b: `d_odom_ab`
  /// is p_b - p_a in the odometry's map frame, `q_odom_a` keyframe a's
  /// attitude there, `sigma` its standard deviation [m]. Levelled at every
  /// evaluation with the latest setOdometryLevelling, or with
  /// config.height_span_keyframe_frame turned into a's frame and back by the
  /// graph's attitude of a.
  void addHeightDifference(int a, int b, const Eigen::Vector3d& d_odom_ab,
                           const Eigen::Quaterniond& q_odom_a, double sigma);
  /// Adds an oriented landmark; a level or plumb prior when config says so.
  int addLandmark(const PlaneLandmark& landmark);
  /// Observation of landmark `plane` by keyframe `kf`: (n_kf, d_kf) oriented like
  /// the landmark, `covariance` of (a1, a2, d) in tangentBasis(n_kf). Returns its index.
  int addObservation(int kf, int plane, const Eigen::Vector3d& n_kf, double d_kf,
                     const Eigen::Matrix3d& covariance);
  /// Leaves an observation out of every later solve (a wrong association:
  /// a robust loss bounds its pull but does not remove it). Its chi2 is still
  /// evaluated; a plane none of whose remaining observations is in a solve's
  /// window is not free in that solve.
  void excludeObservation(int observation);
  bool observationExcluded(int observation) const;

  /// Levenberg-Marquardt from the current estimate: the newest `window`
  /// keyframes and the planes they see are free (window <= 0: everything).
  /// A free plane keeps every observation by the window's keyframes and the
  /// newest GraphConfig::window_held_observations by older (held) ones;
  /// excluded observations are in none.
  GraphSolveStats optimise(int window, int max_iterations);

  int keyframes() const;
  int landmarks() const;
  int observations() const;
  Pose keyframePose(int kf) const;
  PlaneLandmark landmark(int plane) const;
  /// Observations of a landmark so far.
  int observationCount(int plane) const;
  /// Keyframe that made an observation and its landmark.
  int observationKeyframe(int observation) const;
  int observationLandmark(int observation) const;
  /// Squared whitened residual of an observation at the current estimate
  /// (chi-square with 3 dof when the match is right).
  double observationChi2(int observation) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace storey::backend
