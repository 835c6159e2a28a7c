#include "backend/plane_graph.h"

#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <ceres/sphere_manifold.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <unordered_set>

#include "backend/analytic_factors.h"
#include "backend/factors.h"
#include "backend/level_view.h"
#include "backend/plane_math.h"
#include "backend/tilt_prior.h"
#include "common/error.h"

namespace storey::backend {

struct PlaneGraph::Impl {
  struct Keyframe {
    double q[4];  // x y z w (Eigen order)
    double t[3];
    std::unique_ptr<ceres::CostFunction> prior;  // first keyframe: roll/pitch prior
    bool has_tilt_reference = false;             // the odometry's attitude below is set
    Eigen::Quaterniond q_odom_kf = Eigen::Quaterniond::Identity();
    std::vector<int> edges;
    std::vector<int> observations;
  };
  struct Landmark {
    double n[3];
    double d[1];
    std::vector<int> observations;
    std::unique_ptr<ceres::CostFunction> prior;
  };
  struct Edge {
    int a, b;
    std::unique_ptr<ceres::CostFunction> cost;
  };
  struct Observation {
    int kf, plane;
    PlaneObservationFactor factor;
    std::unique_ptr<ceres::CostFunction> cost;  ///< factor's, with the keyframe pose free
    bool excluded = false;                      ///< left out of every solve
  };

  GraphConfig config;
  std::deque<Keyframe> kfs;  // deque: block addresses stay valid
  std::deque<Landmark> planes;
  std::vector<Edge> edges;
  std::vector<Edge> spans;  ///< height spans (addHeightDifference): cost on t_a, t_b only
  std::vector<Observation> observations;
  ceres::EigenQuaternionManifold quaternion_manifold;
  ceres::SphereManifold<3> sphere_manifold;
  ceres::CauchyLoss plane_loss;
  Eigen::Quaterniond q_world_odom = Eigen::Quaterniond::Identity();  // the odometry's levelling

  explicit Impl(const GraphConfig& c) : config(c), plane_loss(c.plane_loss_width) {}

  /// Index into l.observations before which observations by keyframes older
  /// than `first_free` are left out of a solve: all but the newest `cap` of
  /// them (cap <= 0: none left out). The order of the rest is kept.
  std::size_t firstHeldObservation(const Landmark& l, int first_free, int cap) const {
    if (cap <= 0) return 0;
    int held = 0;
    for (std::size_t i = l.observations.size(); i-- > 0;) {
      const Observation& obs = observations[static_cast<std::size_t>(l.observations[i])];
      if (!obs.excluded && obs.kf < first_free && ++held > cap) return i + 1;
    }
    return 0;
  }

  /// Adds keyframe i's pose blocks (and, when free, its priors; costs made
  /// for this solve go to `solve_costs`).
  void addKeyframeBlocks(ceres::Problem& problem, int i, bool constant,
                         std::vector<std::unique_ptr<ceres::CostFunction>>& solve_costs) {
    Keyframe& k = kfs[static_cast<std::size_t>(i)];
    if (problem.HasParameterBlock(k.q)) return;  // constancy is decided once per solve
    problem.AddParameterBlock(k.q, 4, &quaternion_manifold);
    problem.AddParameterBlock(k.t, 3);
    if (constant || (i == 0 && !k.prior)) {
      problem.SetParameterBlockConstant(k.q);
      problem.SetParameterBlockConstant(k.t);
      return;
    }
    if (i == 0) {
      problem.SetParameterBlockConstant(k.t);  // position and (through the prior) yaw: the gauge
      problem.AddResidualBlock(k.prior.get(), nullptr, k.q);
    }
    if (k.has_tilt_reference && config.tilt_prior_sigma > 0.0) {
      // The reference with the odometry's latest levelling (tilt_prior.h).
      solve_costs.emplace_back(
          new TiltPriorCost(q_world_odom * k.q_odom_kf, config.tilt_prior_sigma));
      problem.AddResidualBlock(solve_costs.back().get(), nullptr, k.q);
    }
  }
};

PlaneGraph::PlaneGraph(const GraphConfig& config) : impl_(std::make_unique<Impl>(config)) {}
PlaneGraph::~PlaneGraph() = default;

int PlaneGraph::addKeyframe(const Pose& T_world_kf) {
  Impl::Keyframe k;
  const Eigen::Quaterniond& q = T_world_kf.rotation();
  k.q[0] = q.x();
  k.q[1] = q.y();
  k.q[2] = q.z();
  k.q[3] = q.w();
  for (int i = 0; i < 3; ++i) k.t[i] = T_world_kf.translation()(i);
  const bool first = impl_->kfs.empty();
  impl_->kfs.push_back(std::move(k));
  if (first) setFirstKeyframeAttitude(q);
  return static_cast<int>(impl_->kfs.size()) - 1;
}

void PlaneGraph::setFirstKeyframeAttitude(const Eigen::Quaterniond& q_world_kf) {
  const double tilt = impl_->config.first_tilt_sigma;
  if (impl_->kfs.empty() || tilt <= 0.0) return;
  // Body-frame information: world x/y rotations (tilt) with std `tilt`, yaw held (1e-6 rad).
  const Eigen::Matrix3d R = q_world_kf.toRotationMatrix();
  const Eigen::Vector3d w(1.0 / (tilt * tilt), 1.0 / (tilt * tilt), 1e12);
  const Eigen::Matrix3d info = R.transpose() * w.asDiagonal() * R;
  impl_->kfs.front().prior.reset(
      RotationPriorFactor::create(q_world_kf.normalized(), sqrtInformation<3>(info)));
}

void PlaneGraph::setTiltReference(int kf, const Eigen::Quaterniond& q_odom_kf) {
  Impl::Keyframe& k = impl_->kfs.at(static_cast<std::size_t>(kf));
  k.q_odom_kf = q_odom_kf.normalized();
  k.has_tilt_reference = true;
}

void PlaneGraph::setOdometryLevelling(const Eigen::Quaterniond& q_world_odom) {
  impl_->q_world_odom = q_world_odom.normalized();
}

void PlaneGraph::addRelativePose(int a, int b, const Pose& T_a_b,
                                 const Eigen::Matrix<double, 6, 6>& information) {
  if (a < 0 || b <= a || b >= keyframes()) throw Error("PlaneGraph: bad relative pose keyframes");
  const int index = static_cast<int>(impl_->edges.size());
  const Impl::Keyframe& k_a = impl_->kfs[static_cast<std::size_t>(a)];
  std::unique_ptr<ceres::CostFunction> cost;
  if (impl_->config.heading_frame_edges && k_a.has_tilt_reference) {
    cost = std::make_unique<HeadingRelativePoseCost>(HeadingRelativePoseFactor(
        T_a_b, k_a.q_odom_kf, &impl_->q_world_odom, sqrtInformation<6>(information)));
  } else {
    cost = std::make_unique<RelativePoseCost>(
        RelativePoseFactor(T_a_b, sqrtInformation<6>(information)));
  }
  impl_->edges.push_back({a, b, std::move(cost)});
  impl_->kfs[static_cast<std::size_t>(b)].edges.push_back(index);
  impl_->kfs[static_cast<std::size_t>(a)].edges.push_back(index);
}

void PlaneGraph::addHeightDifference(int a, int b, const Eigen::Vector3d& d_odom_ab,
                                     const Eigen::Quaterniond& q_odom_a, double sigma) {
  if (a < 0 || b <= a || b >= keyframes()) throw Error("PlaneGraph: bad height span keyframes");
  if (impl_->config.height_span_keyframe_frame) {
    impl_->spans.push_back(
        {a, b,
         std::make_unique<KeyframeHeightDifferenceCost>(q_odom_a.conjugate() * d_odom_ab, sigma)});
  } else {
    impl_->spans.push_back(
        {a, b, std::make_unique<HeightDifferenceCost>(d_odom_ab, &impl_->q_world_odom, sigma)});
  }
}

int PlaneGraph::addLandmark(const PlaneLandmark& landmark) {
  Impl::Landmark l;
  const Eigen::Vector3d n = landmark.n_world.normalized();
  for (int i = 0; i < 3; ++i) l.n[i] = n(i);
  l.d[0] = landmark.d_world;
  const GraphConfig& c = impl_->config;
  if (c.level_prior_sigma > 0.0) {
    const double tol_rad = c.level_tolerance_deg * M_PI / 180.0;
    if (isNearlyLevel(n, tol_rad)) {
      l.prior.reset(LevelPriorFactor::create(true, c.level_prior_sigma));
    } else if (std::abs(n.z()) < std::sin(tol_rad)) {
      l.prior.reset(LevelPriorFactor::create(false, c.level_prior_sigma));
    }
  }
  impl_->planes.push_back(std::move(l));
  return static_cast<int>(impl_->planes.size()) - 1;
}

int PlaneGraph::addObservation(int kf, int plane, const Eigen::Vector3d& n_kf, double d_kf,
                               const Eigen::Matrix3d& covariance) {
  if (kf < 0 || kf >= keyframes() || plane < 0 || plane >= landmarks())
    throw Error("PlaneGraph: observation of an unknown keyframe or plane");
  const int index = static_cast<int>(impl_->observations.size());
  const Eigen::Matrix3d information = covariance.inverse();
  const PlaneObservationFactor factor(n_kf.normalized(), d_kf, sqrtInformation<3>(information));
  impl_->observations.push_back(
      {kf, plane, factor, std::make_unique<PlaneObservationCost>(factor)});
  impl_->kfs[static_cast<std::size_t>(kf)].observations.push_back(index);
  impl_->planes[static_cast<std::size_t>(plane)].observations.push_back(index);
  return index;
}

void PlaneGraph::excludeObservation(int o) {
  impl_->observations.at(static_cast<std::size_t>(o)).excluded = true;
}

bool PlaneGraph::observationExcluded(int o) const {
  return impl_->observations.at(static_cast<std::size_t>(o)).excluded;
}

GraphSolveStats PlaneGraph::optimise(int window, int max_iterations) {
  const auto start = std::chrono::steady_clock::now();
  Impl& g = *impl_;
  GraphSolveStats stats;
  const int n = keyframes();
  if (n < 2 || max_iterations <= 0) return stats;
  const int first_free = window > 0 && n > window ? n - window : 0;
  stats.full = first_free == 0;

  // Costs made for this solve (priors, held observations); they outlive
  // `problem`: declared first.
  std::vector<std::unique_ptr<ceres::CostFunction>> solve_costs;
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.enable_fast_removal = false;
  ceres::Problem problem(options);

  std::unordered_set<int> free_planes;
  for (int i = first_free; i < n; ++i) {
    g.addKeyframeBlocks(problem, i, false, solve_costs);
    for (int o : g.kfs[static_cast<std::size_t>(i)].observations) {
      const Impl::Observation& obs = g.observations[static_cast<std::size_t>(o)];
      if (!obs.excluded) free_planes.insert(obs.plane);
    }
  }
  // Odometry edges that touch a free keyframe (the other end held fixed when older).
  for (const Impl::Edge& e : g.edges) {
    if (e.b < first_free) continue;
    g.addKeyframeBlocks(problem, e.a, e.a < first_free, solve_costs);
    g.addKeyframeBlocks(problem, e.b, e.b < first_free, solve_costs);
    Impl::Keyframe& a = g.kfs[static_cast<std::size_t>(e.a)];
    Impl::Keyframe& b = g.kfs[static_cast<std::size_t>(e.b)];
    problem.AddResidualBlock(e.cost.get(), nullptr, a.q, a.t, b.q, b.t);
    ++stats.residual_blocks;
  }
  for (const Impl::Edge& e : g.spans) {
    if (e.b < first_free) continue;
    g.addKeyframeBlocks(problem, e.a, e.a < first_free, solve_costs);
    g.addKeyframeBlocks(problem, e.b, e.b < first_free, solve_costs);
    Impl::Keyframe& a = g.kfs[static_cast<std::size_t>(e.a)];
    Impl::Keyframe& b = g.kfs[static_cast<std::size_t>(e.b)];
    if (g.config.height_span_keyframe_frame) {  // KeyframeHeightDifferenceCost
      problem.AddResidualBlock(e.cost.get(), nullptr, a.q, a.t, b.t);
    } else {
      problem.AddResidualBlock(e.cost.get(), nullptr, a.t, b.t);
    }
    ++stats.residual_blocks;
  }
  // Every observation of a free plane by the window's keyframes; of those by
  // older keyframes (held fixed) the newest window_held_observations, so a
  // windowed solve does not grow with how often its planes were seen before.
  const int held_cap = first_free > 0 ? g.config.window_held_observations : 0;
  for (int p : free_planes) {
    Impl::Landmark& l = g.planes[static_cast<std::size_t>(p)];
    problem.AddParameterBlock(l.n, 3, &g.sphere_manifold);
    problem.AddParameterBlock(l.d, 1);
    if (l.prior) {
      problem.AddResidualBlock(l.prior.get(), nullptr, l.n);
      ++stats.residual_blocks;
    }
    const std::size_t first_held = g.firstHeldObservation(l, first_free, held_cap);
    for (std::size_t i = 0; i < l.observations.size(); ++i) {
      const Impl::Observation& obs = g.observations[static_cast<std::size_t>(l.observations[i])];
      if (obs.excluded) continue;
      if (i < first_held && obs.kf < first_free) {
        ++stats.held_observations_left_out;
        continue;
      }
      Impl::Keyframe& k = g.kfs[static_cast<std::size_t>(obs.kf)];
      if (obs.kf < first_free) {
        // Held keyframe: its pose is a constant of a plane-only factor.
        solve_costs.emplace_back(new HeldPlaneObservationFactor(
            obs.factor, Eigen::Quaterniond(k.q[3], k.q[0], k.q[1], k.q[2]).toRotationMatrix(),
            Eigen::Vector3d(k.t[0], k.t[1], k.t[2])));
        problem.AddResidualBlock(solve_costs.back().get(), &g.plane_loss, l.n, l.d);
      } else {
        g.addKeyframeBlocks(problem, obs.kf, false, solve_costs);
        problem.AddResidualBlock(obs.cost.get(), &g.plane_loss, k.q, k.t, l.n, l.d);
      }
      ++stats.residual_blocks;
    }
  }
  stats.free_keyframes = n - first_free;
  stats.free_planes = static_cast<int>(free_planes.size());

  ceres::Solver::Options solver;
  solver.minimizer_type = ceres::TRUST_REGION;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type =
      ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE) ||
              ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)
          ? ceres::SPARSE_NORMAL_CHOLESKY
          : ceres::DENSE_QR;
  solver.max_num_iterations = max_iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  stats.iterations = static_cast<int>(summary.iterations.size());
  stats.initial_cost = summary.initial_cost;
  stats.final_cost = summary.final_cost;
  stats.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

int PlaneGraph::keyframes() const {
  return static_cast<int>(impl_->kfs.size());
}
int PlaneGraph::landmarks() const {
  return static_cast<int>(impl_->planes.size());
}
int PlaneGraph::observations() const {
  return static_cast<int>(impl_->observations.size());
}

Pose PlaneGraph::keyframePose(int kf) const {
  const Impl::Keyframe& k = impl_->kfs.at(static_cast<std::size_t>(kf));
  return Pose(Eigen::Quaterniond(k.q[3], k.q[0], k.q[1], k.q[2]),
              Eigen::Vector3d(k.t[0], k.t[1], k.t[2]));
}

PlaneLandmark PlaneGraph::landmark(int plane) const {
  const Impl::Landmark& l = impl_->planes.at(static_cast<std::size_t>(plane));
  return {Eigen::Vector3d(l.n[0], l.n[1], l.n[2]), l.d[0]};
}

int PlaneGraph::observationCount(int plane) const {
  return static_cast<int>(impl_->planes.at(static_cast<std::size_t>(plane)).observations.size());
}
int PlaneGraph::observationKeyframe(int o) const {
  return impl_->observations.at(static_cast<std::size_t>(o)).kf;
}
int PlaneGraph::observationLandmark(int o) const {
  return impl_->observations.at(static_cast<std::size_t>(o)).plane;
}

double PlaneGraph::observationChi2(int o) const {
  const Impl::Observation& obs = impl_->observations.at(static_cast<std::size_t>(o));
  const Impl::Keyframe& k = impl_->kfs[static_cast<std::size_t>(obs.kf)];
  const Impl::Landmark& l = impl_->planes[static_cast<std::size_t>(obs.plane)];
  const double* params[] = {k.q, k.t, l.n, l.d};
  double r[3];
  obs.cost->Evaluate(params, r, nullptr);
  return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
}

}  // namespace storey::backend
