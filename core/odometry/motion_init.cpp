#include "odometry/motion_init.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "common/error.h"
#include "common/format.h"
#include "imu/imu_initializer.h"
#include "imu/imu_pose_table.h"
#include "imu/imu_preintegration.h"
#include "imu/imu_state_blocks.h"
#include "imu/so3.h"
#include "odometry/deskew.h"
#include "odometry/feature_frames.h"
#include "odometry/features.h"
#include "odometry/lidar_factors.h"
#include "odometry/scan_matcher.h"
#include "odometry/voxel_map.h"

namespace storey {
namespace {

// Registration of one scan: the guess' uncertainty (a weak prior that only
// decides directions the LiDAR leaves open) and the accuracy assumed of the
// registered poses in the alignment.
constexpr double kGuessSigmaTranslation = 0.10;     // [m]
constexpr double kGuessSigmaRotation = 0.02;        // [rad]
constexpr double kRegisteredSigmaPosition = 0.01;   // [m]
constexpr double kRegisteredSigmaRotation = 0.002;  // [rad]
constexpr int kMinMatches = 30;                     // plane + line matches for a registered scan

/// r = [(p - p0) / sigma_p, 2 vec(q q0^-1) / sigma_r] on the 7-parameter IMU pose block.
struct PosePrior {
  PosePrior(const Pose& T0, double sigma_p, double sigma_r)
      : p0(T0.translation()), q0(T0.rotation()), wp(1.0 / sigma_p), wr(1.0 / sigma_r) {}
  template <typename T>
  bool operator()(const T* pose, T* r) const {
    for (int i = 0; i < 3; ++i) r[i] = (pose[i] - T(p0[i])) * T(wp);
    const Eigen::Quaternion<T> q(pose[6], pose[3], pose[4], pose[5]);
    Eigen::Quaternion<T> d = q * q0.conjugate().cast<T>();
    const T sign = d.w() < T(0) ? T(-1) : T(1);
    r[3] = T(2) * sign * d.x() * T(wr);
    r[4] = T(2) * sign * d.y() * T(wr);
    r[5] = T(2) * sign * d.z() * T(wr);
    return true;
  }
  Eigen::Vector3d p0;
  Eigen::Quaterniond q0;
  double wp, wr;
};

/// Two unit vectors orthogonal to unit u and to each other.
Eigen::Matrix<double, 3, 2> tangentBasis(const Eigen::Vector3d& u) {
  const Eigen::Vector3d a =
      std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d b1 = u.cross(a).normalized();
  Eigen::Matrix<double, 3, 2> B;
  B << b1, u.cross(b1);
  return B;
}

double largestStd(const Eigen::MatrixXd& covariance) {
  return std::sqrt(std::max(0.0, covariance.diagonal().maxCoeff()));
}

/// Deskews `scan` from `guess` (its reference time's state) and extracts its features.
MotionInitScan prepareScan(const Scan& scan, const ImuState& guess,
                           const std::vector<ImuSample>& imu, const OdometryConfig& config,
                           const SensorConfig& sensor) {
  const std::int64_t end_ns =
      guess.stamp_ns + std::max<std::int64_t>(secondsToNs(scan.timeSpan().second), 1'000'000);
  const ImuPoseTable table = ImuPoseTable::fromSamples(guess, imu, end_ns, sensor.imu.gravity);
  const FeatureSet features = extractFeatures(deskewScan(scan, table, sensor), config.features);
  MotionInitScan out;
  out.state_ns = guess.stamp_ns;
  out.T_world_imu = guess.T_world_imu;
  out.planes_imu = toImuFrame(features.planes, sensor.T_imu_lidar);
  out.edges_imu = toImuFrame(features.edges, sensor.T_imu_lidar);
  return out;
}

/// Local maps of registered scans (as the odometry's).
struct LocalMaps {
  LocalMaps(const OdometryConfig& config) : planes(config.local_map), edges(config.local_map) {}
  void add(const MotionInitScan& scan, const SensorConfig& sensor) {
    planes.insert(toWorld(scan.planes_imu, scan.T_world_imu),
                  scan.T_world_imu * sensor.T_imu_lidar.translation());
    edges.insert(toWorld(scan.edges_imu, scan.T_world_imu));
  }
  VoxelMap planes, edges;
};

/// Registers `scan` (features at its guessed pose scan.T_world_imu) to
/// `maps`, pose only with a weak prior at the guess; returns the pose and
/// the number of matches.
Pose registerScan(const MotionInitScan& scan, const LocalMaps& maps, const OdometryConfig& config,
                  const SensorConfig& sensor, int& matches) {
  ImuState guess;
  guess.T_world_imu = scan.T_world_imu;
  ImuStateBlocks blocks = ImuStateBlocks::fromState(guess);
  matches = 0;
  const int rounds = std::max(config.matching_rounds, 3);
  for (int round = 0; round < rounds; ++round) {
    const MatchResult m =
        matchFeatures(scan.planes_imu, scan.edges_imu, blocks.toState(0).T_world_imu, maps.planes,
                      maps.edges, config, sensor.T_imu_lidar.translation());
    matches = static_cast<int>(m.planes.size() + m.lines.size());
    if (matches < kMinMatches) break;
    ceres::Problem problem;
    problem.AddParameterBlock(blocks.pose, ImuStateBlocks::kPoseSize, new ImuPoseManifold());
    problem.AddResidualBlock(new ScanResidualsFactor(m, blocks.pose, config.huber_threshold),
                             nullptr, blocks.pose);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PosePrior, 6, 7>(new PosePrior(
                                 scan.T_world_imu, kGuessSigmaTranslation, kGuessSigmaRotation)),
                             nullptr, blocks.pose);
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = std::max(config.max_iterations, 4);
    options.num_threads = 1;
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
  }
  if (matches < kMinMatches) {
    throw Error("too few LiDAR matches (" + std::to_string(matches) + ") to register the scan at " +
                significantText(nsToSeconds(scan.state_ns), 12) + " s (IMU clock)");
  }
  return blocks.toState(0).T_world_imu;
}

/// The alignment of registered IMU poses with the IMU (steps 2-3 of the header).
struct Alignment {
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d g_world = Eigen::Vector3d::Zero();  ///< with |g| fixed [m/s^2]
  double gravity_norm = 0.0;                          ///< before fixing |g|
  std::vector<Eigen::Vector3d> v_world;               ///< per scan [m/s]
  double position_rms = 0.0;
  double velocity_sigma = 0.0, tilt_sigma = 0.0, gyro_bias_sigma = 0.0, accel_bias_sigma = 0.0;
};

Alignment align(const std::vector<Pose>& T_world_imu, const std::vector<std::int64_t>& t_ns,
                const std::vector<ImuSample>& imu, const Eigen::Vector3d& gyro_bias_lin,
                const OdometryConfig& config, const ImuNoise& noise) {
  const int n = static_cast<int>(T_world_imu.size());
  Alignment out;
  ImuBias bias;
  bias.gyro = gyro_bias_lin;

  // Gyro bias from the rotations since the first scan.
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  const Eigen::Quaterniond q0 = T_world_imu[0].rotation();
  for (int k = 1; k < n; ++k) {
    const ImuPreintegration from_first =
        ImuPreintegration::fromSamples(imu, t_ns[0], t_ns[k], bias, noise);
    const Eigen::Quaterniond measured = q0.conjugate() * T_world_imu[k].rotation();
    const Eigen::Vector3d r = so3::logQuaternion(from_first.deltas().dR.conjugate() * measured);
    const Eigen::Matrix3d& J = from_first.dR_dbg();
    H += J.transpose() * J;
    b += J.transpose() * r;
  }
  const Eigen::Matrix3d H_bg = H + 1e-9 * Eigen::Matrix3d::Identity();
  out.gyro_bias = gyro_bias_lin + H_bg.ldlt().solve(b);
  out.gyro_bias_sigma = kRegisteredSigmaRotation * std::sqrt(2.0) * largestStd(H_bg.inverse());
  bias.gyro = out.gyro_bias;

  // Velocity and gravity from the positions relative to the first scan: each
  // registered position is one measurement, so the equations are independent.
  std::vector<ImuPreintegration> from_first;
  from_first.reserve(n - 1);
  for (int k = 1; k < n; ++k)
    from_first.push_back(ImuPreintegration::fromSamples(imu, t_ns[0], t_ns[k], bias, noise));
  const Eigen::Matrix3d R0 = T_world_imu[0].rotation().toRotationMatrix();
  // x = [v_0 (3), g (3), b_a (3), c (3)], or the same with w (2) for g and
  // g = |g| u + B w: the accelerometer bias b_a with its prior (mean 0,
  // prior_accel_bias_sigma) takes the part of |g| that is the bias along
  // gravity, as the still start does; c is the first scan's position, a
  // measurement like the others (an error of the first registration, e.g.
  // of a map of one scan, is then not taken for a velocity).
  auto solve = [&](const Eigen::Vector3d* u, Eigen::VectorXd& x, Eigen::MatrixXd& covariance,
                   double& position_rms) {
    const int ng = u ? 2 : 3;
    const int ba = 3 + ng, c = ba + 3, nx = c + 3;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3 * n + 3, nx);
    Eigen::VectorXd y = Eigen::VectorXd::Zero(3 * n + 3);
    Eigen::Matrix<double, 3, 2> B;
    if (u) B = tangentBasis(*u);
    std::vector<double> sigmas;
    for (int k = 0; k < n; ++k) {
      // p_k - R_0 dp_0k = c + v_0 T + g T^2 / 2 + R_0 dp/dba b_a
      const ImuPreintegration* s = k > 0 ? &from_first[k - 1] : nullptr;
      const double T = s ? s->duration() : 0.0;
      const double sp =
          std::hypot(kRegisteredSigmaPosition,
                     s ? std::sqrt(s->covariance().block<3, 3>(6, 6).trace() / 3.0) : 0.0);
      Eigen::Vector3d yp = T_world_imu[k].translation();
      const int r = 3 * k;
      A.block<3, 3>(r, 0) = Eigen::Matrix3d::Identity() * T / sp;
      if (u) {
        yp -= 0.5 * T * T * noise.gravity * *u;
        A.block<3, 2>(r, 3) = 0.5 * T * T * B / sp;
      } else {
        A.block<3, 3>(r, 3) = 0.5 * T * T * Eigen::Matrix3d::Identity() / sp;
      }
      if (s) {
        yp -= R0 * s->deltas().dp;
        A.block<3, 3>(r, ba) = R0 * s->dp_dba() / sp;
      }
      A.block<3, 3>(r, c) = Eigen::Matrix3d::Identity() / sp;
      y.segment<3>(r) = yp / sp;
      sigmas.push_back(sp);
    }
    A.block<3, 3>(3 * n, ba) = Eigen::Matrix3d::Identity() / config.prior_accel_bias_sigma;
    const Eigen::MatrixXd N = A.transpose() * A;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(N);
    x = ldlt.solve(A.transpose() * y);
    covariance = ldlt.solve(Eigen::MatrixXd::Identity(nx, nx));
    const Eigen::VectorXd r = A * x - y;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) sum += (r.segment<3>(3 * k) * sigmas[k]).squaredNorm();
    position_rms = std::sqrt(sum / n);
  };

  Eigen::VectorXd x;
  Eigen::MatrixXd covariance;
  solve(nullptr, x, covariance, out.position_rms);
  const Eigen::Vector3d g_free = x.segment<3>(3);
  out.gravity_norm = g_free.norm();
  if (!(std::abs(out.gravity_norm - noise.gravity) <= config.imu_init.max_gravity_error)) {
    throw Error("the LiDAR motion and the IMU agree on a gravity of " +
                significantText(out.gravity_norm) + " m/s^2, not " +
                significantText(noise.gravity) + " +- " +
                significantText(config.imu_init.max_gravity_error) +
                " m/s^2 (wrong extrinsic or time offset, accelerations not in m/s^2, or the "
                "registration failed)");
  }
  Eigen::Vector3d u = g_free / out.gravity_norm;
  for (int iteration = 0; iteration < 4; ++iteration) {
    solve(&u, x, covariance, out.position_rms);
    u = (noise.gravity * u + tangentBasis(u) * x.segment<2>(3)).normalized();
  }
  out.g_world = noise.gravity * u;
  out.accel_bias = x.segment<3>(5);
  const Eigen::Vector3d v0 = x.head<3>();
  out.v_world.resize(n);
  out.v_world[0] = v0;
  for (int k = 1; k < n; ++k) {
    const ImuPreintegration& s = from_first[k - 1];
    out.v_world[k] =
        v0 + out.g_world * s.duration() + R0 * (s.deltas().dv + s.dv_dba() * out.accel_bias);
  }
  out.velocity_sigma = largestStd(covariance.block(0, 0, 3, 3));
  out.tilt_sigma = largestStd(covariance.block(3, 3, 2, 2)) / noise.gravity;
  out.accel_bias_sigma = largestStd(covariance.block(5, 5, 3, 3));
  return out;
}

}  // namespace

MotionInitResult initializeInMotion(const std::vector<ImuSample>& imu,
                                    const std::vector<const Scan*>& scans,
                                    const OdometryConfig& config, const SensorConfig& sensor) {
  const int n = static_cast<int>(scans.size());
  if (n < std::max(3, config.imu_init.motion_min_scans)) {
    throw Error("only " + std::to_string(n) + " scans in the first " +
                significantText(config.imu_init.motion_window) + " s (needs " +
                std::to_string(std::max(3, config.imu_init.motion_min_scans)) + ")");
  }
  const std::int64_t offset_ns = secondsToNs(sensor.time_offset_lidar_to_imu);
  std::vector<std::int64_t> t_ns(n);
  for (int k = 0; k < n; ++k) t_ns[k] = scans[k]->stamp_ns + offset_ns;
  const ImuNoise& noise = sensor.imu;

  // Provisional world frame W': levelled by the mean specific force over the
  // window, rotated into the first scan's IMU frame with the gyro.
  const ImuPreintegration whole =
      ImuPreintegration::fromSamples(imu, t_ns.front(), t_ns.back(), ImuBias(), noise);
  const Eigen::Vector3d mean_force_imu0 = whole.deltas().dv / whole.duration();
  if (!(mean_force_imu0.norm() > 1e-3)) throw Error("the IMU measures no specific force");
  Eigen::Quaterniond q_world_imu0 = gravityAlignedRotation(mean_force_imu0);

  std::vector<ImuState> states(n);
  Alignment alignment;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  MotionInitStats stats;
  std::vector<MotionInitScan> prepared(n);
  int min_matches = 0;
  for (int pass = 0; pass < 2; ++pass) {
    min_matches = std::numeric_limits<int>::max();
    std::vector<Pose> registered(n);
    if (pass == 0) {
      // Incremental: each scan registered to the scans before it. Rotation
      // guessed from the gyro, position at constant velocity.
      LocalMaps maps(config);
      for (int k = 0; k < n; ++k) {
        ImuState guess;
        guess.stamp_ns = t_ns[k];
        if (k == 0) {
          guess.T_world_imu = Pose(q_world_imu0, Eigen::Vector3d::Zero());
        } else {
          const ImuPreintegration step =
              ImuPreintegration::fromSamples(imu, t_ns[k - 1], t_ns[k], guess.bias, noise);
          Eigen::Vector3d v = Eigen::Vector3d::Zero();
          if (k >= 2) {
            v = (registered[k - 1].translation() - registered[k - 2].translation()) /
                nsToSeconds(t_ns[k - 1] - t_ns[k - 2]);
          }
          guess.v_world_imu = v;
          guess.T_world_imu =
              Pose(registered[k - 1].rotation() * step.deltas().dR,
                   registered[k - 1].translation() + v * nsToSeconds(t_ns[k] - t_ns[k - 1]));
        }
        prepared[k] = prepareScan(*scans[k], guess, imu, config, sensor);
        if (k > 0) {
          int matches = 0;
          prepared[k].T_world_imu = registerScan(prepared[k], maps, config, sensor, matches);
          min_matches = std::min(min_matches, matches);
        }
        maps.add(prepared[k], sensor);
        registered[k] = prepared[k].T_world_imu;
      }
    } else {
      // Every scan deskewed with the first pass' states and registered to all
      // the others: a map of one scan (the first's, in the first pass) has
      // plane fits of one scan's noise, which its successors inherit.
      for (int k = 0; k < n; ++k)
        prepared[k] = prepareScan(*scans[k], states[k], imu, config, sensor);
      for (int k = 0; k < n; ++k) {
        LocalMaps maps(config);
        for (int j = 0; j < n; ++j)
          if (j != k) maps.add(prepared[j], sensor);
        int matches = 0;
        registered[k] = registerScan(prepared[k], maps, config, sensor, matches);
        min_matches = std::min(min_matches, matches);
      }
      for (int k = 0; k < n; ++k) prepared[k].T_world_imu = registered[k];
    }
    alignment = align(registered, t_ns, imu, gyro_bias, config, noise);
    gyro_bias = alignment.gyro_bias;
    // Level: W = R_lev W' turns the estimated gravity to (0, 0, -|g|).
    const Eigen::Quaterniond q_lev =
        Eigen::Quaterniond::FromTwoVectors(alignment.g_world, -Eigen::Vector3d::UnitZ());
    for (int k = 0; k < n; ++k) {
      states[k].stamp_ns = t_ns[k];
      states[k].T_world_imu =
          Pose(q_lev * registered[k].rotation(), q_lev * registered[k].translation());
      states[k].v_world_imu = q_lev * alignment.v_world[k];
      states[k].bias.gyro = gyro_bias;
      states[k].bias.accel = alignment.accel_bias;
      prepared[k].T_world_imu = states[k].T_world_imu;
    }
  }
  stats.min_matches = min_matches;

  stats.scans = n;
  stats.window_s = nsToSeconds(t_ns.back() - t_ns.front());
  stats.gravity_norm = alignment.gravity_norm;
  stats.speed_start = states[0].v_world_imu.norm();
  stats.vertical_speed_start = states[0].v_world_imu.z();
  for (int k = 1; k < n; ++k)
    stats.path_length +=
        (states[k].T_world_imu.translation() - states[k - 1].T_world_imu.translation()).norm();
  stats.position_rms = alignment.position_rms;
  stats.velocity_sigma = alignment.velocity_sigma;
  stats.tilt_sigma = alignment.tilt_sigma;
  stats.gyro_bias_sigma = alignment.gyro_bias_sigma;
  stats.accel_bias_sigma = alignment.accel_bias_sigma;

  MotionInitResult result;
  result.state = states[0];
  result.stats = stats;
  result.scans = std::move(prepared);
  return result;
}

}  // namespace storey
