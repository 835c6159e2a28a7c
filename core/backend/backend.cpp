#include "backend/backend.h"

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "backend/keyframe_rule.h"
#include "backend/plane_graph.h"
#include "common/error.h"

namespace storey {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

Pose interpolate(const Pose& a, const Pose& b, double alpha) {
  return Pose(a.rotation().slerp(alpha, b.rotation()),
              (1.0 - alpha) * a.translation() + alpha * b.translation());
}

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json hull(const std::vector<Eigen::Vector3d>& vertices) {
  nlohmann::json out = nlohmann::json::array();
  for (const Eigen::Vector3d& v : vertices) out.push_back(vec(v));
  return out;
}

}  // namespace

struct SrpBackend::Impl {
  struct ScanRecord {
    double time;
    Pose U;  // pure odometry pose (corrections taken out)
  };
  struct Keyframe {
    std::size_t scan;
    double time;
    Pose U;
    int graph_index;
  };
  struct ObservationRecord {
    int keyframe, plane, graph_index;
    Plane plane_keyframe;  // as observed (Hesse form)
    Eigen::Vector3d centroid;            // of the inliers, keyframe frame
    std::vector<Eigen::Vector3d> hull;   // outline on the plane, keyframe frame
    int points;
    double rms;
    double chi2_at_match;
  };

  Config config;
  backend::PlaneGraph graph;
  std::vector<ScanRecord> scans;
  std::vector<Keyframe> kfs;
  std::vector<ObservationRecord> observations;
  std::vector<int> last_seen_kf;  // per landmark
  std::vector<int> observation_count;  // per landmark
  std::vector<double> observation_chi2;  // after finish()
  Pose A;                         // cumulative correction: current odometry frame <- pure frame
  std::vector<Eigen::Vector3f> last_points;  // the newest scan when it is no keyframe
  Pose last_T_current;
  BackendStats stats;
  bool finished = false;

  explicit Impl(const Config& c) : config(c), graph(c.backend.graph) {}

  bool isKeyframe(const Pose& T_current, double time) const {
    if (kfs.empty()) return true;
    return isNewKeyframe(config.backend.keyframes, A * kfs.back().U, kfs.back().time, T_current, time);
  }

  Eigen::Matrix<double, 6, 6> odometryInformation(const Pose& T_a_b) const {
    const GraphConfig& g = config.backend.graph;
    const double dist = T_a_b.translation().norm();
    const double st = g.odometry_sigma_translation + g.odometry_sigma_translation_per_m * dist;
    const double sr = g.odometry_sigma_rotation + g.odometry_sigma_rotation_per_m * dist;
    Eigen::Matrix<double, 6, 1> diag;
    diag << 1 / (st * st), 1 / (st * st), 1 / (st * st), 1 / (sr * sr), 1 / (sr * sr), 1 / (sr * sr);
    return diag.asDiagonal();
  }

  std::optional<Pose> processKeyframe(const std::vector<Eigen::Vector3f>& points, const Pose& T_current) {
    const std::size_t scan_index = scans.size() - 1;
    const Pose& U = scans.back().U;
    // Best current estimate: the last optimised keyframe and the odometry since.
    Pose T_pred = T_current;
    if (!kfs.empty()) {
      const Keyframe& last = kfs.back();
      T_pred = graph.keyframePose(last.graph_index) * (last.U.inverse() * U);
    }
    const int kf_graph = graph.addKeyframe(T_pred);
    const int kf_index = static_cast<int>(kfs.size());
    if (!kfs.empty()) {
      const Keyframe& last = kfs.back();
      const Pose T_a_b = last.U.inverse() * U;
      graph.addRelativePose(last.graph_index, kf_graph, T_a_b, odometryInformation(T_a_b));
    }
    kfs.push_back({scan_index, scans.back().time, U, kf_graph});
    ++stats.keyframes;

    // SRP extraction on the deskewed scan.
    auto t = Clock::now();
    const backend::SrpExtractionResult srps = backend::extractSrps(points, config.backend.extraction);
    stats.ms_extraction.push_back(msSince(t));
    stats.srps += static_cast<std::int64_t>(srps.srps.size());
    if (srps.srps.empty()) ++stats.keyframes_without_srp;
    for (std::size_t i = 0; i < stats.plane_rejects.size(); ++i) stats.plane_rejects[i] += srps.rejects[i];

    // Association with the global plane map predicted in the keyframe.
    t = Clock::now();
    std::vector<backend::PlanePrediction> predictions;
    predictions.reserve(static_cast<std::size_t>(graph.landmarks()));
    const Eigen::Matrix3d R = T_pred.rotationMatrix();
    for (int j = 0; j < graph.landmarks(); ++j) {
      const backend::PlaneLandmark l = graph.landmark(j);
      predictions.push_back({j, R.transpose() * l.n_world, l.d_world - l.n_world.dot(T_pred.translation()),
                             observation_count[static_cast<std::size_t>(j)]});
    }
    const backend::AssociationResult assoc =
        backend::associate(srps.srps, predictions, config.backend.association);
    for (std::size_t i = 0; i < stats.gate_rejects.size(); ++i) stats.gate_rejects[i] += assoc.gate_rejects[i];
    bool constraint = false, revisit = false;
    const int window = config.backend.graph.window_keyframes;
    for (std::size_t i = 0; i < srps.srps.size(); ++i) {
      const backend::DetectedPlane& srp = srps.srps[i];
      const backend::SrpAssociation& a = assoc.srps[i];
      ++stats.outcomes[static_cast<std::size_t>(a.outcome)];
      int plane = -1;
      if (a.outcome == backend::AssociationOutcome::kMatched) {
        plane = a.landmark;
        constraint = true;
        if (window > 0 && kf_index - last_seen_kf[static_cast<std::size_t>(plane)] >= window) revisit = true;
      } else if (a.outcome == backend::AssociationOutcome::kNewPlane) {
        const Eigen::Vector3d n_world = T_pred.rotation() * srp.plane.normal();
        plane = graph.addLandmark({n_world, srp.plane.distance() + n_world.dot(T_pred.translation())});
        last_seen_kf.push_back(kf_index);
        observation_count.push_back(0);
      } else {
        continue;
      }
      const GraphConfig& gc = config.backend.graph;
      const Eigen::Vector3d model_var(gc.plane_sigma_rotation * gc.plane_sigma_rotation,
                                      gc.plane_sigma_rotation * gc.plane_sigma_rotation,
                                      gc.plane_sigma_distance * gc.plane_sigma_distance);
      const int o = graph.addObservation(kf_graph, plane, srp.plane.normal(), srp.plane.distance(),
                                         srp.covariance + Eigen::Matrix3d(model_var.asDiagonal()));
      observations.push_back(
          {kf_index, plane, o, srp.plane, srp.centroid, srp.hull, srp.points, srp.rms, a.chi2});
      last_seen_kf[static_cast<std::size_t>(plane)] = kf_index;
      ++observation_count[static_cast<std::size_t>(plane)];
    }
    stats.ms_association.push_back(msSince(t));
    stats.planes = graph.landmarks();
    stats.observations = graph.observations();
    if (!constraint) return std::nullopt;

    // Optimise: the newest keyframes (pulled to the planes older keyframes
    // saw), the whole graph every full_every solves and at the end (then the
    // correction of a revisited plane reaches back over the whole loop).
    const GraphConfig& g = config.backend.graph;
    const bool full = window <= 0 || (stats.optimisations % std::max(g.full_every, 1)) == 0;
    if (revisit) ++stats.revisits;
    const backend::GraphSolveStats solve = graph.optimise(full ? 0 : window, g.max_iterations);
    ++stats.optimisations;
    if (solve.full) ++stats.full_optimisations;
    stats.ms_optimisation.push_back(solve.ms);
    (solve.full ? stats.ms_full_optimisation : stats.ms_window_optimisation).push_back(solve.ms);
    stats.optimisation_keyframes.push_back(graph.keyframes());

    const Pose C = graph.keyframePose(kf_graph) * T_current.inverse();
    A = C * A;
    return C;
  }
};

void validateBackendConfig(const BackendConfig& c) {
  auto require = [](bool ok, const char* key, const char* what) {
    if (!ok) throw Error(std::string("backend.") + key + ": " + what);
  };
  require(c.keyframes.distance > 0, "keyframes.distance", "must be positive");
  require(c.keyframes.pitch_roll_deg > 0, "keyframes.pitch_roll_deg", "must be positive");
  require(c.keyframes.max_interval >= 0, "keyframes.max_interval", "must be >= 0");
  require(c.graph.first_tilt_sigma >= 0, "graph.first_tilt_sigma", "must be >= 0");
  const SrpExtractionConfig& e = c.extraction;
  require(e.min_points >= 3, "extraction.min_points", "must be >= 3");
  require(e.max_srps >= 1 && e.max_srps <= 3, "extraction.max_srps", "must be within [1, 3]");
  require(e.explained_fraction >= 0 && e.explained_fraction <= 1, "extraction.explained_fraction",
          "must be within [0, 1]");
  require(e.max_detected_planes >= 1, "extraction.max_detected_planes", "must be >= 1");
  require(e.orthogonal_tolerance_deg > 0 && e.orthogonal_tolerance_deg < 45,
          "extraction.orthogonal_tolerance_deg", "must be within (0, 45)");
  require(e.ransac_distance > 0, "extraction.ransac_distance", "must be positive");
  require(e.ransac_iterations >= 1, "extraction.ransac_iterations", "must be >= 1");
  require(e.voxel_size > 0, "extraction.voxel_size", "must be positive");
  require(e.ransac_max_points >= 10, "extraction.ransac_max_points", "must be >= 10");
  require(e.max_range > e.min_range, "extraction.max_range", "must exceed extraction.min_range");
  require(e.min_view_angle_deg >= 0 && e.min_view_angle_deg < 45, "extraction.min_view_angle_deg",
          "must be within [0, 45)");
  require(e.point_sigma > 0, "extraction.point_sigma", "must be positive");
  require(e.max_effective_points >= 3, "extraction.max_effective_points", "must be >= 3");
  const AssociationConfig& a = c.association;
  require(a.angle_gate_deg > 0 && a.angle_gate_deg < 45, "association.angle_gate_deg", "must be within (0, 45)");
  require(a.distance_gate > 0, "association.distance_gate", "must be positive");
  require(a.mahalanobis_gate > 0, "association.mahalanobis_gate", "must be positive");
  require(a.pose_sigma_rotation > 0, "association.pose_sigma_rotation", "must be positive");
  require(a.pose_sigma_translation > 0, "association.pose_sigma_translation", "must be positive");
  require(a.plane_sigma_rotation > 0, "association.plane_sigma_rotation", "must be positive");
  require(a.plane_sigma_distance > 0, "association.plane_sigma_distance", "must be positive");
  require(a.ambiguity_margin >= 0, "association.ambiguity_margin", "must be >= 0");
  require(a.new_plane_separation >= 1, "association.new_plane_separation", "must be >= 1");
  require(a.confirmed_observations >= 1, "association.confirmed_observations", "must be >= 1");
  const GraphConfig& g = c.graph;
  require(g.odometry_sigma_translation > 0, "graph.odometry_sigma_translation", "must be positive");
  require(g.odometry_sigma_translation_per_m >= 0, "graph.odometry_sigma_translation_per_m", "must be >= 0");
  require(g.odometry_sigma_rotation > 0, "graph.odometry_sigma_rotation", "must be positive");
  require(g.odometry_sigma_rotation_per_m >= 0, "graph.odometry_sigma_rotation_per_m", "must be >= 0");
  require(g.plane_loss_width > 0, "graph.plane_loss_width", "must be positive");
  require(g.plane_sigma_rotation >= 0, "graph.plane_sigma_rotation", "must be >= 0");
  require(g.plane_sigma_distance >= 0, "graph.plane_sigma_distance", "must be >= 0");
  require(g.level_prior_sigma >= 0, "graph.level_prior_sigma", "must be >= 0");
  require(g.level_tolerance_deg >= 0 && g.level_tolerance_deg < 45, "graph.level_tolerance_deg",
          "must be within [0, 45)");
  require(g.max_iterations >= 1, "graph.max_iterations", "must be >= 1");
  require(g.window_keyframes >= 0, "graph.window_keyframes", "must be >= 0");
  require(g.full_every >= 1, "graph.full_every", "must be >= 1");
  require(g.final_iterations >= 0, "graph.final_iterations", "must be >= 0");
  require(g.outlier_chi2 > 0, "graph.outlier_chi2", "must be positive");
}

SrpBackend::SrpBackend(const Config& config) : impl_(std::make_unique<Impl>(config)) {
  validateBackendConfig(config.backend);
}
SrpBackend::~SrpBackend() = default;

std::optional<Pose> SrpBackend::addScan(const OdometryResult& scan) {
  Impl& m = *impl_;
  const Pose& T_current = scan.T_world_lidar;
  const double time = scan.deskewed.time();
  m.scans.push_back({time, m.A.inverse() * T_current});
  ++m.stats.scans;
  m.last_points.clear();
  m.last_points.reserve(scan.deskewed.points.size());
  for (const ScanPoint& p : scan.deskewed.points) m.last_points.push_back(p.p);
  m.last_T_current = T_current;
  if (!m.isKeyframe(T_current, time)) return std::nullopt;
  std::optional<Pose> correction = m.processKeyframe(m.last_points, T_current);
  m.last_points.clear();
  return correction;
}

void SrpBackend::finish() {
  Impl& m = *impl_;
  if (m.finished) return;
  m.finished = true;
  // The last scan becomes a keyframe too, so the end of the log is constrained.
  if (!m.last_points.empty()) m.processKeyframe(m.last_points, m.last_T_current);
  const auto t = Clock::now();
  if (m.config.backend.graph.final_iterations > 0 && m.graph.observations() > 0)
    m.graph.optimise(0, m.config.backend.graph.final_iterations);
  m.stats.ms_final_optimisation = msSince(t);
  m.observation_chi2.clear();
  m.stats.wrong_associations = 0;
  for (const auto& o : m.observations) {
    const double chi2 = m.graph.observationChi2(o.graph_index);
    m.observation_chi2.push_back(chi2);
    // A plane seen once is no association (its residual is the level prior's).
    if (chi2 > m.config.backend.graph.outlier_chi2 && m.graph.observationCount(o.plane) > 1)
      ++m.stats.wrong_associations;
  }
}

Trajectory SrpBackend::trajectory() const {
  const Impl& m = *impl_;
  Trajectory out;
  out.reserve(m.scans.size());
  std::size_t a = 0;  // the last keyframe at or before the scan
  for (std::size_t s = 0; s < m.scans.size(); ++s) {
    const Impl::ScanRecord& scan = m.scans[s];
    if (m.kfs.empty()) {
      out.push_back({scan.time, scan.U});
      continue;
    }
    while (a + 1 < m.kfs.size() && m.kfs[a + 1].scan <= s) ++a;
    const Impl::Keyframe& ka = m.kfs[a];
    const Pose from_a = m.graph.keyframePose(ka.graph_index) * (ka.U.inverse() * scan.U);
    if (s < ka.scan || a + 1 >= m.kfs.size()) {
      out.push_back({scan.time, from_a});
      continue;
    }
    const Impl::Keyframe& kb = m.kfs[a + 1];
    const Pose from_b = m.graph.keyframePose(kb.graph_index) * (kb.U.inverse() * scan.U);
    const double span = kb.time - ka.time;
    const double alpha = span > 0 ? std::clamp((scan.time - ka.time) / span, 0.0, 1.0) : 0.0;
    out.push_back({scan.time, interpolate(from_a, from_b, alpha)});
  }
  return out;
}

Trajectory SrpBackend::odometry() const {
  Trajectory out;
  out.reserve(impl_->scans.size());
  for (const auto& s : impl_->scans) out.push_back({s.time, s.U});
  return out;
}

Trajectory SrpBackend::keyframes() const {
  Trajectory out;
  for (const auto& k : impl_->kfs) out.push_back({k.time, impl_->graph.keyframePose(k.graph_index)});
  return out;
}

std::string SrpBackend::planesJson() const {
  const Impl& m = *impl_;
  std::vector<nlohmann::json> per_plane(static_cast<std::size_t>(m.graph.landmarks()),
                                        nlohmann::json::array());
  for (std::size_t i = 0; i < m.observations.size(); ++i) {
    const auto& o = m.observations[i];
    const double chi2 = i < m.observation_chi2.size() ? m.observation_chi2[i]
                                                       : m.graph.observationChi2(o.graph_index);
    per_plane[static_cast<std::size_t>(o.plane)].push_back(
        {{"keyframe", o.keyframe},
         {"time", m.kfs[static_cast<std::size_t>(o.keyframe)].time},
         {"normal", vec(o.plane_keyframe.normal())},
         {"distance", o.plane_keyframe.distance()},
         {"centroid", vec(o.centroid)},
         {"hull", hull(o.hull)},
         {"points", o.points},
         {"fit_rms_m", o.rms},
         {"residual_chi2", chi2},
         {"outlier", chi2 > m.config.backend.graph.outlier_chi2 && m.graph.observationCount(o.plane) > 1}});
  }
  nlohmann::json planes = nlohmann::json::array();
  for (int j = 0; j < m.graph.landmarks(); ++j) {
    const backend::PlaneLandmark l = m.graph.landmark(j);
    const Plane hesse(l.n_world, l.d_world);
    const auto& obs = per_plane[static_cast<std::size_t>(j)];
    planes.push_back({{"id", j},
                      {"normal", vec(hesse.normal())},
                      {"distance", hesse.distance()},
                      {"facing", vec(-l.n_world)},
                      {"observation_count", obs.size()},
                      {"observations", obs}});
  }
  nlohmann::json doc = {
      {"format", "storey planes, version 1"},
      {"frame", "world (z up, origin at the LiDAR's start)"},
      {"convention",
       "Hesse normal form n . x = d, |n| = 1, d >= 0, metres; `facing` points from the plane to "
       "the side it was seen from; observations are in the keyframe's LiDAR frame (keyframe = "
       "index into keyframes.tum; centroid of the inliers; hull = their convex outline on the "
       "plane, counter-clockwise seen from the normal's side), residual_chi2 is the whitened squared residual after the "
       "final optimisation (3 dof)"},
      {"keyframes", m.kfs.size()},
      {"planes", planes}};
  return doc.dump(1);
}

const BackendStats& SrpBackend::stats() const { return impl_->stats; }

}  // namespace storey
