#include "backend/srp_backend.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "backend/fit_noise.h"
#include "backend/keyframe_rule.h"
#include "backend/level_view.h"
#include "backend/odometry_information.h"
#include "backend/plane_graph.h"
#include "backend/solve_schedule.h"
#include "common/error.h"
#include "common/stopwatch.h"

namespace storey {

namespace {

using Clock = std::chrono::steady_clock;
// SRPs seen before the rough-fit gate acts: the median of fewer is not the
// run's noise yet.
constexpr int kFitNoiseMinSrps = 20;

double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

Pose interpolate(const Pose& a, const Pose& b, double alpha) {
  return Pose(a.rotation().slerp(alpha, b.rotation()),
              (1.0 - alpha) * a.translation() + alpha * b.translation());
}

}  // namespace

struct SrpBackend::Impl {
  struct ScanRecord {
    double time;
    Pose T_odom_lidar;  // the odometry's pose (its own world frame)
  };
  struct Keyframe {
    std::size_t scan;
    double time;
    Pose T_odom_lidar;
    int graph_index;
    double path;  // the odometry's path length from the first scan [m]
  };
  struct ObservationRecord {
    int keyframe, plane, graph_index;
    Plane plane_keyframe;               // as observed (Hesse form)
    Eigen::Vector3d centroid;           // of the inliers, keyframe frame
    std::vector<Eigen::Vector3d> hull;  // outline on the plane, keyframe frame
    int points;
    double rms;
    double chi2_at_match;
  };

  BackendConfig config;
  backend::PlaneGraph graph;
  std::vector<ScanRecord> scans;
  std::vector<Keyframe> kfs;
  std::vector<ObservationRecord> observations;
  std::vector<int> last_seen_kf;         // per landmark
  std::vector<Plane> newest_view;        // per landmark, in its keyframe last_seen_kf
  double path = 0.0;                     // the odometry's path length so far [m]
  std::vector<int> observation_count;    // per landmark
  std::vector<double> observation_chi2;  // after finish()
  backend::FitNoise fit_noise;           // the run's SRP fit RMS (rough-fit gate)
  int since_whole_solve = -1;            // optimisations since the last whole-graph one
  // The graph's correction of the odometry as of the last solve:
  // T_world_lidar = T_world_odom * T_odom_lidar (the odometry's levelling of
  // its first scan until the first solve).
  Pose T_world_odom;
  // The odometry's latest levelling of its map frame (its gravity estimate).
  Eigen::Quaterniond q_world_odom = Eigen::Quaterniond::Identity();
  std::vector<Eigen::Vector3f> keyframe_points;  // a keyframe's scan for the extraction
  bool last_is_keyframe = false;                 // the newest scan
  Pose last_T_world_lidar;

  void processKeyframe(const Scan& deskewed, const Pose& T_world_lidar) {
    keyframe_points.clear();
    keyframe_points.reserve(deskewed.points.size());
    for (const ScanPoint& p : deskewed.points) keyframe_points.push_back(p.p);
    processKeyframe(keyframe_points, T_world_lidar);
  }
  BackendStats stats;
  bool finished = false;

  explicit Impl(const BackendConfig& c)
      : config(c), graph(c.graph), fit_noise(c.association.max_rms_ratio, kFitNoiseMinSrps) {}

  bool isKeyframe(const Pose& T_world_lidar, double time) const {
    if (kfs.empty()) return true;
    return isNewKeyframe(config.keyframes, T_world_odom * kfs.back().T_odom_lidar, kfs.back().time,
                         T_world_lidar, time);
  }

  /// Adds the newest scan as a keyframe (T_world_lidar: its odometry pose
  /// corrected as of the last solve); optimises when a plane constraint appears.
  void processKeyframe(const std::vector<Eigen::Vector3f>& points, const Pose& T_world_lidar) {
    const auto start = Clock::now();
    const double cpu_start = threadCpuSeconds();
    processKeyframeTimed(points, T_world_lidar);
    stats.ms_keyframe.push_back(msSince(start));
    stats.cpu_ms_keyframe.push_back(1e3 * (threadCpuSeconds() - cpu_start));
  }

  void processKeyframeTimed(const std::vector<Eigen::Vector3f>& points, const Pose& T_world_lidar) {
    const std::size_t scan_index = scans.size() - 1;
    const Pose& T_odom_lidar = scans.back().T_odom_lidar;
    // Best current estimate: the last optimised keyframe and the odometry since.
    Pose T_pred = T_world_lidar;
    if (!kfs.empty()) {
      const Keyframe& last = kfs.back();
      T_pred = graph.keyframePose(last.graph_index) * (last.T_odom_lidar.inverse() * T_odom_lidar);
    }
    const int kf_graph = graph.addKeyframe(T_pred);
    graph.setTiltReference(kf_graph, T_odom_lidar.rotation());
    const int kf_index = static_cast<int>(kfs.size());
    if (!kfs.empty()) {
      const Keyframe& last = kfs.back();
      const Pose T_a_b = last.T_odom_lidar.inverse() * T_odom_lidar;
      graph.addRelativePose(
          last.graph_index, kf_graph, T_a_b,
          backend::odometryEdgeInformation(config.graph, last.T_odom_lidar, T_odom_lidar));
    }
    const std::size_t span = static_cast<std::size_t>(config.graph.height_span_keyframes);
    if (span > 0 && kfs.size() >= span) {
      const Keyframe& first = kfs[kfs.size() - span];
      graph.addHeightDifference(first.graph_index, kf_graph,
                                T_odom_lidar.translation() - first.T_odom_lidar.translation(),
                                first.T_odom_lidar.rotation(), config.graph.height_span_sigma);
    }
    kfs.push_back({scan_index, scans.back().time, T_odom_lidar, kf_graph, path});
    ++stats.keyframes;

    // SRP extraction on the deskewed scan.
    auto t = Clock::now();
    backend::SrpExtractionResult srps = backend::extractSrps(points, config.extraction);
    stats.ms_extraction.push_back(msSince(t));
    stats.srps += static_cast<std::int64_t>(srps.srps.size());
    if (srps.srps.empty()) ++stats.keyframes_without_srp;
    for (std::size_t i = 0; i < stats.plane_rejects.size(); ++i)
      stats.plane_rejects[i] += srps.rejects[i];

    // Rough fits (against the SRPs of the keyframes before) take no part in
    // the association; every SRP then adds to the run's fit noise.
    t = Clock::now();
    // (The SRPs are moved, not copied: their outlines are the bulk.)
    std::vector<double> fit_rms;
    fit_rms.reserve(srps.srps.size());
    for (const backend::DetectedPlane& srp : srps.srps) fit_rms.push_back(srp.rms);
    std::vector<backend::DetectedPlane> usable = std::move(srps.srps);
    usable.erase(
        std::remove_if(
            usable.begin(), usable.end(),
            [&](const backend::DetectedPlane& srp) {
              if (!fit_noise.rough(srp.rms)) return false;
              ++stats.outcomes[static_cast<std::size_t>(backend::AssociationOutcome::kRoughFit)];
              return true;
            }),
        usable.end());
    for (double rms : fit_rms) fit_noise.add(rms);
    stats.srp_rms_median = fit_noise.median();

    // Association with the global plane map predicted in the keyframe.
    std::vector<backend::PlanePrediction> predictions;
    predictions.reserve(static_cast<std::size_t>(graph.landmarks()));
    const Eigen::Matrix3d R = T_pred.rotationMatrix();
    for (int j = 0; j < graph.landmarks(); ++j) {
      const backend::PlaneLandmark l = graph.landmark(j);
      backend::PlanePrediction p{j, R.transpose() * l.n_world,
                                 l.d_world - l.n_world.dot(T_pred.translation()),
                                 observation_count[static_cast<std::size_t>(j)]};
      const double track = config.association.track_distance;
      const Keyframe* seen =
          track > 0.0 ? &kfs[static_cast<std::size_t>(last_seen_kf[static_cast<std::size_t>(j)])]
                      : nullptr;
      if (seen && path - seen->path <= track) {
        // The newest view moved into this keyframe by the odometry alone.
        const Pose T_kf_view = T_odom_lidar.inverse() * seen->T_odom_lidar;
        const Plane tracked = newest_view[static_cast<std::size_t>(j)].transformed(T_kf_view);
        p.tracked = true;
        p.n_track_kf = tracked.normal();
        p.d_track_kf = tracked.distance();
      }
      predictions.push_back(p);
    }
    const backend::AssociationResult assoc = backend::associate(
        usable, predictions, config.association, R.transpose() * Eigen::Vector3d::UnitZ());
    for (std::size_t i = 0; i < stats.gate_rejects.size(); ++i)
      stats.gate_rejects[i] += assoc.gate_rejects[i];
    bool constraint = false, revisit = false;
    const int window = config.graph.window_keyframes;
    for (std::size_t i = 0; i < usable.size(); ++i) {
      const backend::DetectedPlane& srp = usable[i];
      const backend::SrpAssociation& a = assoc.srps[i];
      ++stats.outcomes[static_cast<std::size_t>(a.outcome)];
      int plane = -1;
      if (a.outcome == backend::AssociationOutcome::kMatched) {
        plane = a.landmark;
        constraint = true;
        if (window > 0 && kf_index - last_seen_kf[static_cast<std::size_t>(plane)] >= window)
          revisit = true;
      } else if (a.outcome == backend::AssociationOutcome::kNewPlane) {
        const Eigen::Vector3d n_world = T_pred.rotation() * srp.plane.normal();
        plane =
            graph.addLandmark({n_world, srp.plane.distance() + n_world.dot(T_pred.translation())});
        last_seen_kf.push_back(kf_index);
        newest_view.push_back(srp.plane);
        observation_count.push_back(0);
      } else {
        continue;
      }
      const GraphConfig& gc = config.graph;
      const Eigen::Vector3d model_var(gc.plane_sigma_rotation * gc.plane_sigma_rotation,
                                      gc.plane_sigma_rotation * gc.plane_sigma_rotation,
                                      gc.plane_sigma_distance * gc.plane_sigma_distance);
      const int o = graph.addObservation(kf_graph, plane, srp.plane.normal(), srp.plane.distance(),
                                         srp.covariance + Eigen::Matrix3d(model_var.asDiagonal()));
      observations.push_back(
          {kf_index, plane, o, srp.plane, srp.centroid, srp.hull, srp.points, srp.rms, a.chi2});
      last_seen_kf[static_cast<std::size_t>(plane)] = kf_index;
      newest_view[static_cast<std::size_t>(plane)] = srp.plane;
      ++observation_count[static_cast<std::size_t>(plane)];
    }
    stats.ms_association.push_back(msSince(t));
    stats.planes = graph.landmarks();
    stats.observations = graph.observations();
    if (!constraint) return;

    // Optimise: the newest keyframes (pulled to the planes older keyframes
    // saw), the whole graph on the schedule of solve_schedule.h and at the
    // end (then the correction of a revisited plane reaches back over the
    // whole loop).
    const GraphConfig& g = config.graph;
    levelFirstKeyframe();
    const bool full = backend::wholeGraphSolveDue(g, since_whole_solve, graph.keyframes());
    since_whole_solve = full ? 1 : since_whole_solve + 1;
    if (revisit) ++stats.revisits;
    const backend::GraphSolveStats solve = graph.optimise(full ? 0 : window, g.max_iterations);
    ++stats.optimisations;
    if (solve.full) ++stats.full_optimisations;
    stats.ms_optimisation.push_back(solve.ms);
    (solve.full ? stats.ms_full_optimisation : stats.ms_window_optimisation).push_back(solve.ms);
    stats.optimisation_keyframes.push_back(graph.keyframes());

    // The correction the solve made at this keyframe, composed as the
    // odometry's poses after it will need it.
    const Pose T_corrected_current = graph.keyframePose(kf_graph) * T_world_lidar.inverse();
    T_world_odom = T_corrected_current * T_world_odom;
  }

  /// The first keyframe's roll/pitch prior: its odometry attitude levelled by
  /// the odometry's latest gravity estimate. The relative poses are rigid, so
  /// a better estimate turns the graph as a whole instead of bending it.
  void levelFirstKeyframe() {
    if (kfs.empty()) return;
    graph.setFirstKeyframeAttitude(q_world_odom * kfs.front().T_odom_lidar.rotation());
    graph.setOdometryLevelling(q_world_odom);
  }

  /// Final pose of the LiDAR for every scan: the odometry since the keyframe
  /// before it, corrected by interpolating the corrections of the keyframes
  /// on either side.
  Trajectory trajectory() const {
    Trajectory out;
    out.reserve(scans.size());
    std::size_t a = 0;  // the last keyframe at or before the scan
    for (std::size_t s = 0; s < scans.size(); ++s) {
      const ScanRecord& scan = scans[s];
      if (kfs.empty()) {
        out.push_back({scan.time, scan.T_odom_lidar});
        continue;
      }
      while (a + 1 < kfs.size() && kfs[a + 1].scan <= s) ++a;
      const Keyframe& ka = kfs[a];
      const Pose from_a =
          graph.keyframePose(ka.graph_index) * (ka.T_odom_lidar.inverse() * scan.T_odom_lidar);
      if (s < ka.scan || a + 1 >= kfs.size()) {
        out.push_back({scan.time, from_a});
        continue;
      }
      const Keyframe& kb = kfs[a + 1];
      const Pose from_b =
          graph.keyframePose(kb.graph_index) * (kb.T_odom_lidar.inverse() * scan.T_odom_lidar);
      const double span = kb.time - ka.time;
      const double alpha = span > 0 ? std::clamp((scan.time - ka.time) / span, 0.0, 1.0) : 0.0;
      out.push_back({scan.time, interpolate(from_a, from_b, alpha)});
    }
    return out;
  }

  /// The front end's own trajectory (continuous; what it is on its own),
  /// levelled by its last gravity estimate.
  Trajectory odometry() const {
    const Pose T_level(q_world_odom, Eigen::Vector3d::Zero());
    Trajectory out;
    out.reserve(scans.size());
    for (const ScanRecord& s : scans) out.push_back({s.time, T_level * s.T_odom_lidar});
    return out;
  }

  Trajectory keyframes() const {
    Trajectory out;
    for (const Keyframe& k : kfs) out.push_back({k.time, graph.keyframePose(k.graph_index)});
    return out;
  }

  /// An observation whose residual at the current estimate is beyond the
  /// gate. A plane seen once is no association (its residual is the level
  /// prior's).
  bool isWrongAssociation(const ObservationRecord& o, double chi2) const {
    return chi2 > config.graph.outlier_chi2 && graph.observationCount(o.plane) > 1;
  }

  /// Reported as a wrong association: left out of the last solve, or beyond
  /// the gate after it.
  bool isOutlier(const ObservationRecord& o, double chi2) const {
    return graph.observationExcluded(o.graph_index) || isWrongAssociation(o, chi2);
  }

  /// Leaves the views of level surfaces that are tilted under the current
  /// estimate out of later solves (level_view.h); returns how many.
  int excludeTiltedLevelViews() {
    const double deg = M_PI / 180.0;
    const double max_tilt = config.graph.level_view_max_tilt_deg * deg;
    if (max_tilt <= 0.0) return 0;
    int excluded = 0;
    for (const ObservationRecord& o : observations) {
      if (graph.observationExcluded(o.graph_index)) continue;
      const Eigen::Vector3d n_view_world =
          graph.keyframePose(kfs[static_cast<std::size_t>(o.keyframe)].graph_index).rotation() *
          o.plane_keyframe.normal();
      if (!backend::isTiltedLevelView(graph.landmark(o.plane).n_world, n_view_world,
                                      config.graph.level_tolerance_deg * deg, max_tilt))
        continue;
      graph.excludeObservation(o.graph_index);
      ++excluded;
    }
    return excluded;
  }

  /// Leaves the wrong associations at the current estimate out of later
  /// solves; returns how many were newly left out.
  int excludeWrongAssociations() {
    int excluded = 0;
    for (const ObservationRecord& o : observations) {
      if (graph.observationExcluded(o.graph_index) ||
          !isWrongAssociation(o, graph.observationChi2(o.graph_index)))
        continue;
      graph.excludeObservation(o.graph_index);
      ++excluded;
    }
    return excluded;
  }

  /// The global planes with their observations (after finish(): residuals of the final solve).
  PlaneMap planeMap() const {
    PlaneMap map;
    map.keyframes = static_cast<long>(kfs.size());
    map.planes.resize(static_cast<std::size_t>(graph.landmarks()));
    for (int j = 0; j < graph.landmarks(); ++j) {
      const backend::PlaneLandmark l = graph.landmark(j);
      const Plane hesse(l.n_world, l.d_world);
      GlobalPlane& plane = map.planes[static_cast<std::size_t>(j)];
      plane.id = j;
      plane.normal_world = hesse.normal();
      plane.distance_world = hesse.distance();
      plane.facing_world = -l.n_world;
    }
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const ObservationRecord& o = observations[i];
      const double chi2 =
          i < observation_chi2.size() ? observation_chi2[i] : graph.observationChi2(o.graph_index);
      PlaneObservation obs;
      obs.keyframe = o.keyframe;
      obs.time = kfs[static_cast<std::size_t>(o.keyframe)].time;
      obs.normal_keyframe = o.plane_keyframe.normal();
      obs.distance_keyframe = o.plane_keyframe.distance();
      obs.centroid_keyframe = o.centroid;
      obs.hull_keyframe = o.hull;
      obs.points = o.points;
      obs.fit_rms = o.rms;
      obs.residual_chi2 = chi2;
      obs.outlier = isOutlier(o, chi2);
      map.planes[static_cast<std::size_t>(o.plane)].observations.push_back(std::move(obs));
    }
    return map;
  }
};

SrpBackend::SrpBackend(const BackendConfig& config) : impl_(std::make_unique<Impl>(config)) {
  config.validate();
}
SrpBackend::~SrpBackend() = default;

BackendDecision SrpBackend::addScan(double time, const Pose& T_odom_lidar,
                                    const Eigen::Quaterniond& q_world_odom, const Scan& deskewed) {
  Impl& m = *impl_;
  m.q_world_odom = q_world_odom;
  if (m.scans.empty()) m.T_world_odom = Pose(q_world_odom, Eigen::Vector3d::Zero());
  const Pose T_world_lidar = m.T_world_odom * T_odom_lidar;
  if (!m.scans.empty())
    m.path += (T_odom_lidar.translation() - m.scans.back().T_odom_lidar.translation()).norm();
  m.scans.push_back({time, T_odom_lidar});
  ++m.stats.scans;
  m.last_T_world_lidar = T_world_lidar;
  m.last_is_keyframe = m.isKeyframe(T_world_lidar, time);
  if (m.last_is_keyframe) m.processKeyframe(deskewed, T_world_lidar);
  return {m.last_is_keyframe, T_world_lidar};
}

SlamResult SrpBackend::finish(const Scan& last_deskewed) {
  Impl& m = *impl_;
  if (m.finished) throw Error("internal: SrpBackend::finish called twice");
  m.finished = true;
  // The last scan becomes a keyframe too, so the end of the log is constrained.
  if (!m.last_is_keyframe && !last_deskewed.points.empty()) {
    m.processKeyframe(last_deskewed, m.last_T_world_lidar);
    m.last_is_keyframe = true;
  }
  std::vector<Eigen::Vector3f>().swap(m.keyframe_points);
  const auto t = Clock::now();
  m.levelFirstKeyframe();
  m.stats.tilted_level_views = m.excludeTiltedLevelViews();
  if (m.config.graph.final_iterations > 0 && m.graph.observations() > 0) {
    m.graph.optimise(0, m.config.graph.final_iterations);
    // The observations the solve shows to be wrong associations pull the
    // graph even under the robust loss (Cauchy bounds an outlier's pull, it
    // does not remove it): left out, and the graph solved once more.
    if (m.excludeWrongAssociations() > 0) m.graph.optimise(0, m.config.graph.final_iterations);
  }
  m.stats.ms_final_optimisation = msSince(t);
  m.observation_chi2.clear();
  m.stats.wrong_associations = 0;
  for (const auto& o : m.observations) {
    const double chi2 = m.graph.observationChi2(o.graph_index);
    m.observation_chi2.push_back(chi2);
    if (m.isOutlier(o, chi2)) ++m.stats.wrong_associations;
  }
  SlamResult result;
  result.odometry = m.odometry();
  result.trajectory = m.trajectory();
  result.keyframes = m.keyframes();
  result.planes = m.planeMap();
  result.stats = m.stats;
  return result;
}

}  // namespace storey
