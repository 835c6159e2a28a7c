#include "odometry/odometry.h"

#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <sstream>

#include "common/error.h"
#include "common/log.h"
#include "common/parallel_chunks.h"
#include "common/stopwatch.h"
#include "imu/imu_factor.h"
#include "imu/imu_initializer.h"
#include "imu/imu_pose_table.h"
#include "imu/so3.h"
#include "odometry/deskew.h"
#include "odometry/feature_frames.h"
#include "odometry/features.h"
#include "odometry/imu_gap_fill.h"
#include "odometry/lidar_factors.h"
#include "odometry/motion_prior.h"
#include "odometry/state_prior.h"

namespace storey {

struct LidarInertialOdometry::Frame {
  std::int64_t scan_stamp_ns = 0;  // LiDAR clock
  std::int64_t state_ns = 0;       // IMU clock
  ImuStateBlocks blocks;
  std::unique_ptr<ImuPreintegration> from_previous;  // null for the first frame
  std::vector<Eigen::Vector3d> planes_imu, edges_imu;
  MatchResult matches;
  Scan deskewed;
  OdometryScanStats stats;
  bool in_map = false;       // features inserted into the local map
  MotionPrior motion_prior;  // used while this frame is the window's oldest
  // With odometry.marginalise_pose, the prior on its whole state while it is
  // the window's oldest (none for the log's first frame: its pose stays fixed).
  std::unique_ptr<StatePrior> state_prior;

  ImuState state() const { return blocks.toState(state_ns); }
};

namespace {

using Clock = std::chrono::steady_clock;

/// A dropout is filled with the mean rate of the second before it.
constexpr std::int64_t kDropoutFillMeanSpanNs = 1'000'000'000;

bool hasDropout(const ImuSignal& signal, double gap_threshold) {
  return std::any_of(signal.knots.begin(), signal.knots.end(), [&](const ImuKnot& k) {
    return k.dropout || k.sample_spacing > gap_threshold;
  });
}

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Smallest eigenvalue of the marginal information of block `a` (rows/cols
/// 0-2 or 3-5) of a 6x6 information matrix, i.e. of H_aa - H_ab H_bb^-1 H_ba;
/// returns every eigenvalue (ascending).
Eigen::Vector3d marginalEigenvalues(const Eigen::Matrix<double, 6, 6>& H, int a) {
  const int b = 3 - a;
  const Eigen::Matrix3d Haa = H.block<3, 3>(a, a), Hab = H.block<3, 3>(a, b),
                        Hbb = H.block<3, 3>(b, b) + 1e-9 * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S = Haa - Hab * Hbb.ldlt().solve(Hab.transpose());
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues();
}

/// LiDAR-only normal equations of `matches` at T_world_imu in the world
/// tangent [dp, dtheta]: H = sum w J^T J / sigma^2, b = sum w J^T e / sigma^2
/// (e the residual [m]); a plane match's J is [n^T, (R y x n)^T], a line's
/// [U, -U [R y]x] with U = -[u]x. w is the Huber weight of the whitened
/// residual at huber_k as in the solve, 1 when huber_k <= 0.
void lidarNormalEquations(const MatchResult& matches, const Pose& T_world_imu, double huber_k,
                          Eigen::Matrix<double, 6, 6>& H, Eigen::Matrix<double, 6, 1>& b) {
  H.setZero();
  b.setZero();
  const auto weight = [huber_k](double whitened_norm) {
    return huber_k <= 0.0 || whitened_norm <= huber_k ? 1.0 : huber_k / whitened_norm;
  };
  const Eigen::Quaterniond q_world_imu = T_world_imu.rotation();
  for (const PlaneMatch& m : matches.planes) {
    const Eigen::Vector3d y_world = q_world_imu * m.y_imu;
    const double e = m.n_world.dot(y_world + T_world_imu.translation()) - m.d_world;
    Eigen::Matrix<double, 1, 6> J;
    J << m.n_world.transpose(), y_world.cross(m.n_world).transpose();
    const double w = weight(std::abs(e) / m.sigma) / (m.sigma * m.sigma);
    H += w * J.transpose() * J;
    b += w * J.transpose() * e;
  }
  for (const LineMatch& m : matches.lines) {
    const Eigen::Vector3d y_world = q_world_imu * m.y_imu;
    const Eigen::Vector3d e = (y_world + T_world_imu.translation() - m.a_world).cross(m.u_world);
    const Eigen::Matrix3d U = -so3::skew(m.u_world);
    Eigen::Matrix<double, 3, 6> J;
    J << U, -U * so3::skew(y_world);
    const double w = weight(e.norm() / m.sigma) / (m.sigma * m.sigma);
    H += w * J.transpose() * J;
    b += w * J.transpose() * e;
  }
}

}  // namespace

LidarInertialOdometry::LidarInertialOdometry(const OdometryConfig& config,
                                             const SensorConfig& sensor)
    : config_(config),
      sensor_(sensor),
      time_offset_ns_(secondsToNs(sensor.time_offset_lidar_to_imu)),
      plane_map_(config.local_map),
      edge_map_(config.local_map) {
  parallel_ = std::make_unique<ParallelChunks>(config_.threads);
}

LidarInertialOdometry::~LidarInertialOdometry() = default;

void LidarInertialOdometry::addImu(const ImuSample& sample) {
  if (!imu_.empty() && sample.stamp_ns <= imu_.back().stamp_ns) return;  // reader drops these
  if (!imu_.empty() && isImuDropout(imu_.back(), sample, sensor_.imu)) {
    const std::vector<ImuSample> fill =
        fillImuGap(imu_.back().stamp_ns, sample.stamp_ns, continuedMotion(), sensor_.imu);
    imu_.insert(imu_.end(), fill.begin(), fill.end());
  }
  imu_.push_back(sample);
  tryProcess(false);
}

ImuGapMotion LidarInertialOdometry::continuedMotion() const {
  // The gyro's mean rate over the last second; before the first scan (the
  // initialisation's data) the mean force too, exact at rest.
  const std::int64_t at_ns = imu_.back().stamp_ns;
  const ImuMean mean = meanOfMeasured(imu_, at_ns, kDropoutFillMeanSpanNs);
  ImuGapMotion motion;
  motion.gyro = mean.gyro;
  motion.accel = mean.accel;
  if (window_.empty() || window_.back()->state_ns > at_ns) return motion;
  // Else constant velocity from the newest state carried to the gap's start
  // (the scans inside the gap wait for the IMU: the newest is before it).
  const Frame& newest = *window_.back();
  ImuState state = newest.state();
  if (at_ns > newest.state_ns)
    state = ImuPreintegration::fromSamples(imu_, newest.state_ns, at_ns, state.bias, sensor_.imu)
                .predict(state);
  motion.state_known = true;
  motion.q_world_imu = state.T_world_imu.rotation();
  motion.g_world = tiltedGravity(tilt_, sensor_.imu.gravity);
  motion.bias = state.bias;
  return motion;
}

void LidarInertialOdometry::addScan(Scan scan) {
  pending_.push_back(std::move(scan));
  tryProcess(false);
}

void LidarInertialOdometry::finish() {
  tryProcess(true);
  while (!window_.empty()) {
    emit(*window_.front());
    window_.pop_front();
  }
}

bool LidarInertialOdometry::nextResult(OdometryResult& result) {
  if (results_.empty()) return false;
  result = std::move(results_.front());
  results_.pop_front();
  return true;
}

bool LidarInertialOdometry::initialise(bool at_end) {
  if (!still_failed_) {
    const double span = nsToSeconds(imu_.back().stamp_ns - imu_.front().stamp_ns);
    if (span < config_.imu_init.still_window && !at_end) return false;
    try {
      const ImuInitResult init = initializeImuFromStill(imu_, sensor_.imu, config_.imu_init);
      initial_state_ = init.state;
      std::ostringstream os;
      os << "IMU initialised from " << init.stats.samples << " still samples: gyro std "
         << init.stats.gyro_std << " rad/s, |accel| " << init.stats.mean_accel_norm << " m/s^2";
      logInfo(os.str());
      return true;
    } catch (const Error& e) {
      if (!config_.imu_init.motion_start) throw;
      still_failed_ = true;
      initialisation_.not_still = e.what();
    }
  }
  return initialiseInMotion(at_end);
}

bool LidarInertialOdometry::initialiseInMotion(bool at_end) {
  const auto fail = [&](const std::string& why) {
    return Error("the log does not start at rest (" + initialisation_.not_still +
                 "), and initialising while moving failed: " + why +
                 " (odometry.imu_init in the config)");
  };
  // Scans the IMU does not reach back to, or without points, cannot be used.
  while (!pending_.empty() &&
         (pending_.front().points.empty() ||
          pending_.front().stamp_ns + time_offset_ns_ <= imu_.front().stamp_ns)) {
    ++(pending_.front().points.empty() ? drops_.empty : drops_.before_first_imu);
    pending_.pop_front();
    front_span_ns_.reset();
  }
  if (pending_.empty()) {
    if (at_end) throw fail("the log has no scan inside the IMU data");
    return false;
  }
  const std::int64_t first_ns = pending_.front().stamp_ns + time_offset_ns_;
  const std::int64_t window_end_ns = first_ns + secondsToNs(config_.imu_init.motion_window);
  if (imu_.back().stamp_ns < window_end_ns + 200'000'000 && !at_end) return false;
  std::vector<const Scan*> scans;
  for (const Scan& scan : pending_) {
    const std::int64_t ref_ns = scan.stamp_ns + time_offset_ns_;
    if (ref_ns > window_end_ns) break;
    const std::int64_t end_ns = ref_ns + secondsToNs(std::max(0.0f, scan.timeSpan().second));
    if (scan.points.empty() || end_ns > imu_.back().stamp_ns) continue;
    if (!scans.empty() && ref_ns <= scans.back()->stamp_ns + time_offset_ns_) continue;
    scans.push_back(&scan);
  }
  if (scans.empty() || scans.front() != &pending_.front())
    throw fail("the IMU data do not cover the first scan");
  MotionInitResult init;
  try {
    init = initializeInMotion(imu_, scans, config_, sensor_);
  } catch (const Error& e) {
    throw fail(e.what());
  }
  initial_state_ = init.state;
  seed_scans_ = std::move(init.scans);
  initialisation_.in_motion = true;
  initialisation_.motion = init.stats;
  std::ostringstream os;
  os << std::setprecision(3) << "the log does not start at rest: initialised while moving from "
     << init.stats.scans << " scans over " << init.stats.window_s << " s (speed "
     << init.stats.speed_start << " m/s, gravity found " << init.stats.gravity_norm
     << " m/s^2, tilt std " << init.stats.tilt_sigma * 1e3 << " mrad)";
  logInfo(os.str());
  return true;
}

void LidarInertialOdometry::tryProcess(bool at_end) {
  if (!initialised_) {
    if (imu_.empty()) {
      if (at_end && !pending_.empty()) throw Error("the log has point clouds but no IMU samples");
      return;
    }
    // Throws with an explanation when neither a still nor a moving start works.
    if (!initialise(at_end)) return;
    initialised_ = true;
  }
  while (!pending_.empty()) {
    const Scan& scan = pending_.front();
    const std::int64_t ref_ns = scan.stamp_ns + time_offset_ns_;
    if (!front_span_ns_) front_span_ns_ = secondsToNs(std::max(0.0f, scan.timeSpan().second));
    const std::int64_t end_ns = ref_ns + *front_span_ns_;
    if (imu_.back().stamp_ns < end_ns) {
      if (!at_end) return;
      // The log ends inside this scan: it cannot be deskewed (nor can any
      // later one); they are dropped and counted.
      drops_.after_last_imu += static_cast<std::int64_t>(pending_.size());
      pending_.clear();
      front_span_ns_.reset();
      return;
    }
    if (scan.points.empty()) {
      ++drops_.empty;
    } else if (ref_ns <= imu_.front().stamp_ns) {
      ++drops_.before_first_imu;
    } else {
      processScan(scan);
    }
    pending_.pop_front();
    front_span_ns_.reset();
    trimImu();
  }
}

void LidarInertialOdometry::trimImu() {
  if (window_.empty() || imu_.size() < 8192) return;
  // Keep everything from one second before the newest state (the next
  // preintegration starts there and needs a sample at or before it).
  const std::int64_t keep_from = window_.back()->state_ns - 1'000'000'000;
  const auto first_kept =
      std::lower_bound(imu_.begin(), imu_.end(), keep_from,
                       [](const ImuSample& s, std::int64_t t) { return s.stamp_ns < t; });
  if (first_kept - imu_.begin() > 1) imu_.erase(imu_.begin(), first_kept - 1);
}

void LidarInertialOdometry::processScan(const Scan& scan) {
  const auto start = Clock::now();
  const double cpu_start = threadCpuSeconds();
  const OdometryConfig& cfg = config_;
  const double gravity = sensor_.imu.gravity;
  auto frame = std::make_unique<Frame>();
  frame->scan_stamp_ns = scan.stamp_ns;
  frame->state_ns = scan.stamp_ns + time_offset_ns_;
  frame->stats.points = static_cast<std::int64_t>(scan.points.size());
  const std::int64_t table_end_ns =
      frame->state_ns + std::max<std::int64_t>(secondsToNs(scan.timeSpan().second), 1'000'000);

  // 1. Predict the state at the scan's reference time.
  auto t = Clock::now();
  ImuState previous;
  if (window_.empty()) {
    if (frame->state_ns <= initial_state_.stamp_ns) {
      previous = initial_state_;  // still at the start: the initial state holds
      previous.stamp_ns = frame->state_ns;
    } else {
      const ImuPreintegration from_init = ImuPreintegration::fromSamples(
          imu_, initial_state_.stamp_ns, frame->state_ns, initial_state_.bias, sensor_.imu);
      previous = from_init.predict(initial_state_);
      previous.stamp_ns = frame->state_ns;
    }
    if (!origin_set_) {
      // World frame: gravity-aligned (from the IMU initialisation), origin at
      // the LiDAR's start position, yaw such that the LiDAR's x axis points
      // along world +x (whatever the IMU's mounting), unless it is vertical.
      const Pose& T_imu_lidar = sensor_.T_imu_lidar;
      Eigen::Quaterniond q_world_imu = previous.T_world_imu.rotation();
      const Eigen::Vector3d lidar_x_world =
          q_world_imu * (T_imu_lidar.rotation() * Eigen::Vector3d::UnitX());
      if (lidar_x_world.head<2>().norm() > 0.1) {
        const double yaw = std::atan2(lidar_x_world.y(), lidar_x_world.x());
        q_world_imu = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * q_world_imu;
        previous.v_world_imu =
            Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * previous.v_world_imu;
      }
      previous.T_world_imu = Pose(q_world_imu, -(q_world_imu * T_imu_lidar.translation()));
      origin_set_ = true;
      seedLocalMap(previous.T_world_imu);
    }
    frame->blocks = ImuStateBlocks::fromState(previous);
    // The still start levels the world frame with the accelerometer: a bias
    // orthogonal to gravity is a tilt of |b| / |g| (imu.md), hence the tilt's prior.
    // Started in motion: the initialisation's own uncertainties where larger.
    const MotionInitStats& moving = initialisation_.motion;
    const bool in_motion = initialisation_.in_motion;
    frame->motion_prior = diagonalMotionPrior(
        Eigen::Map<const Vector9d>(frame->blocks.motion), Eigen::Map<const Eigen::Vector2d>(tilt_),
        std::max(cfg.prior_velocity_sigma, in_motion ? moving.velocity_sigma : 0.0),
        std::max(cfg.prior_gyro_bias_sigma, in_motion ? moving.gyro_bias_sigma : 0.0),
        cfg.prior_accel_bias_sigma,
        std::max(cfg.prior_accel_bias_sigma / gravity, in_motion ? moving.tilt_sigma : 0.0));
  } else {
    const Frame& last = *window_.back();
    previous = last.state();
    if (nsToSeconds(frame->state_ns - last.state_ns) > cfg.max_scan_gap) {
      std::ostringstream os;
      os << "gap of " << nsToSeconds(frame->state_ns - last.state_ns)
         << " s between scans at t = " << nsToSeconds(frame->scan_stamp_ns)
         << " s: the IMU alone carries the motion across it";
      logInfo(os.str());  // the reader's fault check warned (faults.lidar_gap)
    }
    frame->from_previous = std::make_unique<ImuPreintegration>(ImuPreintegration::fromSamples(
        imu_, last.state_ns, frame->state_ns, previous.bias, sensor_.imu));
    ImuState predicted = frame->from_previous->predict(previous);
    predicted.stamp_ns = frame->state_ns;
    frame->blocks = ImuStateBlocks::fromState(predicted);
  }
  frame->stats.ms_preintegration = msSince(t);

  // 2. Deskew with the IMU-propagated motion.
  t = Clock::now();
  const ImuPoseTable table = ImuPoseTable::fromSamples(previous, imu_, table_end_ns, gravity);
  frame->deskewed = deskewScan(scan, table, sensor_);
  frame->stats.ms_deskew = msSince(t);

  // 3. Features.
  t = Clock::now();
  const FeatureSet features = extractFeatures(frame->deskewed, cfg.features, parallel_.get());
  frame->planes_imu = toImuFrame(features.planes, sensor_.T_imu_lidar);
  frame->edges_imu = toImuFrame(features.edges, sensor_.T_imu_lidar);
  frame->stats.plane_features = static_cast<std::int64_t>(features.planes.size());
  frame->stats.edge_features = static_cast<std::int64_t>(features.edges.size());
  frame->stats.feature_rejects = features.rejected;
  frame->stats.ms_features = msSince(t);

  frame->in_map = std::binary_search(seeded_ns_.begin(), seeded_ns_.end(), frame->state_ns);
  window_.push_back(std::move(frame));
  Frame& newest = *window_.back();
  if (window_.size() > static_cast<std::size_t>(std::max(cfg.window_size, 2))) slide();
  if (window_.size() >= 2 && !plane_map_.empty()) optimise(newest);
  if (window_.size() == 1 && plane_map_.empty()) slide();  // the very first scan seeds the map
  newest.stats.ms_total = msSince(start);
  newest.stats.cpu_ms_total = 1e3 * (threadCpuSeconds() - cpu_start);
}

void LidarInertialOdometry::seedLocalMap(const Pose& T_world_imu_first) {
  if (seed_scans_.empty()) return;
  // The initialisation's frame to the odometry's: its first scan onto ours.
  const Pose T_world_init = T_world_imu_first * seed_scans_.front().T_world_imu.inverse();
  for (const MotionInitScan& scan : seed_scans_) {
    const Pose T_world_imu = T_world_init * scan.T_world_imu;
    plane_map_.insert(toWorld(scan.planes_imu, T_world_imu),
                      T_world_imu * sensor_.T_imu_lidar.translation());
    edge_map_.insert(toWorld(scan.edges_imu, T_world_imu));
    seeded_ns_.push_back(scan.state_ns);
  }
  std::sort(seeded_ns_.begin(), seeded_ns_.end());
  seed_scans_.clear();
  seed_scans_.shrink_to_fit();
}

void LidarInertialOdometry::optimise(Frame& newest) {
  const OdometryConfig& cfg = config_;
  // A dense sensor's planar features beyond max_matched_planes are thinned
  // evenly (every one still enters the local map).
  std::vector<Eigen::Vector3d> thinned;
  const std::size_t budget = static_cast<std::size_t>(std::max(cfg.max_matched_planes, 0));
  if (budget > 0 && newest.planes_imu.size() > budget) {
    thinned.reserve(budget);
    for (std::size_t i = 0; i < budget; ++i)
      thinned.push_back(newest.planes_imu[i * newest.planes_imu.size() / budget]);
  }
  const std::vector<Eigen::Vector3d>& matched_planes =
      thinned.empty() ? newest.planes_imu : thinned;
  for (int round = 0; round < std::max(cfg.matching_rounds, 1); ++round) {
    auto t = Clock::now();
    newest.matches = matchFeatures(
        matched_planes, newest.edges_imu, newest.blocks.toState(newest.state_ns).T_world_imu,
        plane_map_, edge_map_, cfg, sensor_.T_imu_lidar.translation(), parallel_.get());
    newest.stats.ms_matching += msSince(t);

    t = Clock::now();
    ceres::Problem problem;
    for (auto& frame : window_) addImuStateBlocks(problem, frame->blocks);
    problem.AddParameterBlock(tilt_, 2);
    Frame& oldest = *window_.front();
    if (oldest.state_prior) {
      problem.AddResidualBlock(new StatePriorFactor(*oldest.state_prior), nullptr,
                               oldest.blocks.pose, oldest.blocks.motion, tilt_);
    } else {
      problem.SetParameterBlockConstant(oldest.blocks.pose);
      problem.AddResidualBlock(new MotionPriorFactor(oldest.motion_prior), nullptr,
                               oldest.blocks.motion, tilt_);
    }
    for (std::size_t i = 1; i < window_.size(); ++i) {
      Frame& previous = *window_[i - 1];
      Frame& frame = *window_[i];
      const ImuBias bias = previous.state().bias;
      if (frame.from_previous->needsRepropagation(bias, cfg.preintegration))
        frame.from_previous->repropagate(bias);
      problem.AddResidualBlock(new ImuGravityFactor(*frame.from_previous), nullptr,
                               previous.blocks.pose, previous.blocks.motion, frame.blocks.pose,
                               frame.blocks.motion, tilt_);
    }
    // The oldest frame's own scan only when its pose is free.
    for (std::size_t i = oldest.state_prior ? 0 : 1; i < window_.size(); ++i) {
      Frame& frame = *window_[i];
      if (frame.matches.planes.empty() && frame.matches.lines.empty()) continue;
      problem.AddResidualBlock(
          new CompressedScanFactor(frame.matches, frame.blocks.pose, cfg.huber_threshold), nullptr,
          frame.blocks.pose);
    }
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    options.max_num_iterations = std::max(cfg.max_iterations, 1);
    options.num_threads = 1;
    options.logging_type = ceres::SILENT;
    options.minimizer_progress_to_stdout = false;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    newest.stats.solver_iterations += static_cast<int>(summary.iterations.size());
    newest.stats.ms_optimisation += msSince(t);
  }
  newest.stats.plane_matches = static_cast<std::int64_t>(newest.matches.planes.size());
  newest.stats.line_matches = static_cast<std::int64_t>(newest.matches.lines.size());
  newest.stats.match_rejects = newest.matches.rejected;

  // Degeneracy: LiDAR-only information of the newest pose.
  Eigen::Matrix<double, 6, 6> H;
  Eigen::Matrix<double, 6, 1> b;
  lidarNormalEquations(newest.matches, newest.blocks.toState(newest.state_ns).T_world_imu, 0.0, H,
                       b);
  const Eigen::Vector3d translation_eigen = marginalEigenvalues(H, 0);
  const Eigen::Vector3d rotation_eigen = marginalEigenvalues(H, 3);
  const auto stdOf = [](double eigenvalue) { return 1.0 / std::sqrt(std::max(eigenvalue, 1e-12)); };
  newest.stats.lidar_translation_std_max = stdOf(translation_eigen(0));
  for (int i = 0; i < 3; ++i) {
    if (stdOf(translation_eigen(i)) > cfg.degenerate_translation_std)
      ++newest.stats.degenerate_translation_directions;
    if (stdOf(rotation_eigen(i)) > cfg.degenerate_rotation_std)
      ++newest.stats.degenerate_rotation_directions;
  }
}

void LidarInertialOdometry::slide() {
  Frame& oldest = *window_.front();
  if (!oldest.in_map) {
    const Pose T_world_imu = oldest.state().T_world_imu;
    const Eigen::Vector3d lidar_world = T_world_imu * sensor_.T_imu_lidar.translation();
    plane_map_.insert(toWorld(oldest.planes_imu, T_world_imu), lidar_world);
    edge_map_.insert(toWorld(oldest.edges_imu, T_world_imu));
    // Dropping far voxels walks the whole map: once per metre travelled is enough.
    const Eigen::Vector3d sensor_world = T_world_imu.translation();
    if ((sensor_world - last_map_trim_position_).norm() > 1.0) {
      plane_map_.removeFar(sensor_world);
      edge_map_.removeFar(sensor_world);
      last_map_trim_position_ = sensor_world;
    }
    oldest.in_map = true;
  }
  if (window_.size() == 1) return;  // the first frame stays as the window's fixed anchor
  Frame& next = *window_[1];
  // One prior or the other: a frame with a state prior never uses its motion prior.
  if (config_.marginalise_pose) {
    Eigen::Matrix<double, 6, 6> lidar_information;
    Eigen::Matrix<double, 6, 1> gradient;
    lidarNormalEquations(oldest.matches, oldest.state().T_world_imu, config_.huber_threshold,
                         lidar_information, gradient);
    next.state_prior = std::make_unique<StatePrior>(propagateStatePrior(
        oldest.state_prior.get(), oldest.motion_prior, ImuGravityFactor(*next.from_previous),
        oldest.blocks.pose, oldest.blocks.motion, next.blocks.pose, next.blocks.motion, tilt_,
        lidar_information));
  } else {
    next.motion_prior = propagateMotionPrior(
        oldest.motion_prior, ImuGravityFactor(*next.from_previous), oldest.blocks.pose,
        oldest.blocks.motion, next.blocks.pose, next.blocks.motion, tilt_,
        config_.pose_sigma_translation, config_.pose_sigma_rotation);
  }
  emit(oldest);
  window_.pop_front();
}

bool LidarInertialOdometry::lidarOnlyRotation(const Frame& frame, Eigen::Quaterniond& q) const {
  // One Gauss-Newton step of the frame's LiDAR residuals alone from its final
  // pose (world tangent [dp, dtheta], robust weights as in the solve): where
  // the LiDAR would put the frame without the IMU.
  if (frame.stats.degenerate_rotation_directions > 0 ||
      frame.matches.planes.size() + frame.matches.lines.size() < 100)
    return false;
  const Pose T_world_imu = frame.state().T_world_imu;
  Eigen::Matrix<double, 6, 6> H;
  Eigen::Matrix<double, 6, 1> g;
  lidarNormalEquations(frame.matches, T_world_imu, config_.huber_threshold, H, g);
  const Eigen::Matrix<double, 6, 1> step = -H.ldlt().solve(g);
  if (!step.allFinite()) return false;
  q = so3::expQuaternion(step.tail<3>()) * T_world_imu.rotation();
  return true;
}

void LidarInertialOdometry::emit(Frame& frame) {
  // The time offset: the LiDAR's rotation between this scan and the one
  // emitted before it against the gyro's.
  Eigen::Quaterniond q_lidar;
  const bool rotation_valid = lidarOnlyRotation(frame, q_lidar);
  if (rotation_valid && last_rotation_valid_ && frame.from_previous &&
      frame.from_previous->signal().knots.size() >= 2 &&
      !hasDropout(frame.from_previous->signal(), imuGapThreshold(sensor_.imu))) {
    const ImuBias bias = frame.state().bias;
    const ImuSignal& signal = frame.from_previous->signal();
    time_offset_.add(last_lidar_rotation_.conjugate() * q_lidar,
                     frame.from_previous->correctedDeltas(bias).dR,
                     signal.knots.front().gyro - bias.gyro, signal.knots.back().gyro - bias.gyro);
  }
  last_rotation_valid_ = rotation_valid;
  last_lidar_rotation_ = q_lidar;

  OdometryResult result;
  result.scan_stamp_ns = frame.scan_stamp_ns;
  result.state = frame.state();
  result.T_odom_lidar = result.state.T_world_imu * sensor_.T_imu_lidar;
  // Output frame: the map frame levelled by the estimated gravity direction
  // (g_map = Exp([t, 0]) g, so Exp(-[t, 0]) maps it to (0, 0, -|g|)).
  result.q_world_odom =
      Eigen::Quaterniond(so3::expMatrix(-Eigen::Vector3d(tilt_[0], tilt_[1], 0.0)));
  const Pose T_output_map(result.q_world_odom, Eigen::Vector3d::Zero());
  result.state.T_world_imu = T_output_map * result.state.T_world_imu;
  result.state.v_world_imu = T_output_map.rotation() * result.state.v_world_imu;
  result.deskewed = std::move(frame.deskewed);
  result.stats = frame.stats;
  results_.push_back(std::move(result));
}

}  // namespace storey
