#include "eval/registration_bias.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <utility>
#include <variant>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/statistics.h"
#include "common/time.h"
#include "eval/association.h"
#include "io/log_reader.h"
#include "odometry/features.h"
#include "odometry/scan_matcher.h"
#include "odometry/voxel_map.h"

namespace storey::eval {

const char* toString(PlaneClass c) {
  switch (c) {
    case PlaneClass::kFloorLike:
      return "floor-like";
    case PlaneClass::kWall:
      return "wall";
    case PlaneClass::kSlanted:
      return "slanted";
    case PlaneClass::kCeilingLike:
      return "ceiling-like";
    case PlaneClass::kCount:
      break;
  }
  return "unknown";
}

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// The truth at t, or nothing outside it or in one of its gaps.
std::optional<Pose> truePose(const Trajectory& truth, double t, const AssociationOptions& options) {
  Pose T_world_lidar;
  if (truthAt(truth, t, options, T_world_lidar) != TruthCoverage::kCovered) return std::nullopt;
  return T_world_lidar;
}

/// The scan with every point moved to the scan's stamp with the true motion
/// (T_lidar(stamp)^-1 T_lidar(stamp + point time)); nothing when the truth
/// does not cover the scan. With `imu_truth` (T_world_imu at the IMU's rate)
/// every point gets its own true pose, T_world_imu(t) T_imu_lidar; without
/// it the LiDAR truth (one pose a scan) is interpolated between the first
/// and the last firing time, which misses the motion's curvature within the
/// revolution (a hand-held sensor's sway: a few mrad).
std::optional<Scan> deskewWithTruth(const Scan& scan, const Trajectory& truth,
                                    const Trajectory* imu_truth, const Pose& T_imu_lidar,
                                    const AssociationOptions& options, Pose& T_world_lidar) {
  const double stamp = nsToSeconds(scan.stamp_ns);
  Scan out = scan;
  if (imu_truth != nullptr) {
    const std::optional<Pose> imu_at_stamp = truePose(*imu_truth, stamp, options);
    if (!imu_at_stamp) return std::nullopt;
    T_world_lidar = *imu_at_stamp * T_imu_lidar;
    // Both truths describe one motion: a calibration that is not the
    // simulation's shows here, not as a bias.
    if (const std::optional<Pose> lidar_at_stamp = truePose(truth, stamp, options)) {
      const Pose T_delta = lidar_at_stamp->inverse() * T_world_lidar;
      const double angle = Eigen::AngleAxisd(T_delta.rotation()).angle();
      if (T_delta.translation().norm() > 0.01 || angle > 0.01) {
        char message[256];
        std::snprintf(message, sizeof(message),
                      "registration bias: the IMU truth with the calibration's T_imu_lidar puts "
                      "the LiDAR %.3f m and %.4f rad away from the LiDAR truth at t = %.3f s; "
                      "is --calibration the walk's?",
                      T_delta.translation().norm(), angle, stamp);
        throw Error(message);
      }
    }
    const Pose T_ref_world = T_world_lidar.inverse();
    // The points of one firing share a time: one lookup for them.
    double last_time = std::numeric_limits<double>::quiet_NaN();
    Pose T_ref_lidar;
    for (ScanPoint& p : out.points) {
      if (!(p.time == last_time)) {
        const std::optional<Pose> imu_at = truePose(*imu_truth, stamp + p.time, options);
        if (!imu_at) return std::nullopt;
        T_ref_lidar = T_ref_world * (*imu_at * T_imu_lidar);
        last_time = p.time;
      }
      p.p = (T_ref_lidar * p.p.cast<double>()).cast<float>();
    }
    return out;
  }
  const std::optional<Pose> at_stamp = truePose(truth, stamp, options);
  if (!at_stamp) return std::nullopt;
  T_world_lidar = *at_stamp;
  const auto [first, last] = scan.timeSpan();
  const std::optional<Pose> at_first = truePose(truth, stamp + first, options);
  const std::optional<Pose> at_last = truePose(truth, stamp + last, options);
  if (!at_first || !at_last) return std::nullopt;
  const Pose T_ref_world = at_stamp->inverse();
  const StampedPose a{stamp + first, T_ref_world * *at_first};
  const StampedPose b{stamp + last, T_ref_world * *at_last};
  for (ScanPoint& p : out.points) {
    const Pose T_ref_lidar = interpolatePose(a, b, stamp + p.time);
    p.p = (T_ref_lidar * p.p.cast<double>()).cast<float>();
  }
  return out;
}

PlaneClass classify(const PlaneMatch& m, const Eigen::Vector3d& sensor_world) {
  const double nz = std::abs(m.n_world.z());
  if (nz < 0.3) return PlaneClass::kWall;
  if (nz <= 0.9) return PlaneClass::kSlanted;
  // Height of the plane straight above or below the sensor.
  const double plane_z =
      (m.d_world - m.n_world.x() * sensor_world.x() - m.n_world.y() * sensor_world.y()) /
      m.n_world.z();
  return plane_z > sensor_world.z() ? PlaneClass::kCeilingLike : PlaneClass::kFloorLike;
}

/// The Gauss-Newton step of the point-to-plane cost at T_world_lidar, with
/// the odometry's Huber weights, in the world-frame tangent [dp, dtheta].
RegistrationStep stepAtPose(const MatchResult& matches, const Pose& T_world_lidar,
                            double huber_threshold) {
  RegistrationStep step;
  Matrix6 H = Matrix6::Zero();
  std::array<Vector6, kPlaneClasses> g;
  for (Vector6& x : g) x.setZero();
  const Eigen::Vector3d sensor_world = T_world_lidar.translation();
  for (const PlaneMatch& m : matches.planes) {
    const Eigen::Vector3d x = T_world_lidar * m.y_imu;
    const double r = m.n_world.dot(x) - m.d_world;
    const double whitened = std::abs(r) / m.sigma;
    const double huber = whitened > huber_threshold ? huber_threshold / whitened : 1.0;
    const double w = huber / (m.sigma * m.sigma);
    // x = Exp(dtheta) R y + t + dp: d r / d dp = n, d r / d dtheta = (R y) x n.
    Vector6 J;
    J << m.n_world, (x - sensor_world).cross(m.n_world);
    H += w * J * J.transpose();
    const int c = static_cast<int>(classify(m, sensor_world));
    g[static_cast<std::size_t>(c)] += w * J * r;
    ++step.class_matches[static_cast<std::size_t>(c)];
  }
  step.matches = static_cast<int>(matches.planes.size());
  const Eigen::LDLT<Matrix6> solver(H + 1e-9 * Matrix6::Identity());
  Vector6 total = Vector6::Zero();
  for (std::size_t c = 0; c < g.size(); ++c) {
    const Vector6 part = -solver.solve(g[c]);
    step.class_dz[c] = part(2);
    total += part;
  }
  step.dp = total.head<3>();
  step.dtheta = total.tail<3>();
  return step;
}

template <typename Keep>
BiasSummary summariseSteps(const std::vector<RegistrationStep>& steps, Keep&& keep) {
  BiasSummary out;
  std::vector<double> abs_dz, abs_dp;
  for (const RegistrationStep& s : steps) {
    if (!keep(s)) continue;
    ++out.scans;
    out.mean_dp += s.dp;
    abs_dz.push_back(std::abs(s.dp.z()));
    abs_dp.push_back(s.dp.norm());
    for (std::size_t c = 0; c < kPlaneClasses; ++c) out.class_mean_dz[c] += s.class_dz[c];
  }
  if (out.scans == 0) return out;
  const double n = static_cast<double>(out.scans);
  out.mean_dp /= n;
  for (double& x : out.class_mean_dz) x /= n;
  out.median_abs_dz = quantile(abs_dz, 0.5);
  out.p95_abs_dp = quantile(abs_dp, 0.95);
  return out;
}

void summarise(RegistrationBiasResult& result) {
  const auto& steps = result.steps;
  if (steps.empty()) return;
  const BiasSummary all = summariseSteps(steps, [](const RegistrationStep&) { return true; });
  result.mean_dp = all.mean_dp;
  result.class_mean_dz = all.class_mean_dz;
  result.median_abs_dz = all.median_abs_dz;
  result.p95_abs_dp = all.p95_abs_dp;

  // One-second windows (disjoint, from the first evaluated scan).
  std::vector<BiasWindow> windows;
  for (const RegistrationStep& s : steps) {
    const double start =
        steps.front().since_start + std::floor(s.since_start - steps.front().since_start);
    if (windows.empty() || windows.back().since_start != start)
      windows.push_back({start, s.position_true.z(), 0.0, 0});
    windows.back().mean_dz += s.dp.z();
    ++windows.back().scans;
  }
  for (BiasWindow& w : windows) w.mean_dz /= static_cast<double>(w.scans);
  std::stable_sort(windows.begin(), windows.end(), [](const BiasWindow& a, const BiasWindow& b) {
    return std::abs(a.mean_dz) > std::abs(b.mean_dz);
  });
  windows.resize(std::min<std::size_t>(windows.size(), 5));
  result.worst_windows = windows;
}

}  // namespace

double heightAboveFloor(double z_lidar, const std::vector<double>& floor_elevations) {
  double below = -std::numeric_limits<double>::infinity();
  for (double f : floor_elevations)
    if (f < z_lidar) below = std::max(below, f);
  return std::isfinite(below) ? z_lidar - below : std::numeric_limits<double>::quiet_NaN();
}

void stairsSplit(RegistrationBiasResult& result, const std::vector<double>& floor_elevations,
                 double tolerance) {
  if (floor_elevations.empty() || result.steps.empty()) return;
  std::vector<double> heights, finite;  // per step (NaN: no floor below); the finite ones
  heights.reserve(result.steps.size());
  for (const RegistrationStep& s : result.steps) {
    heights.push_back(heightAboveFloor(s.position_true.z(), floor_elevations));
    if (std::isfinite(heights.back())) finite.push_back(heights.back());
  }
  result.split = true;
  result.walking_height = finite.empty() ? 0.0 : quantile(std::move(finite), 0.5);
  for (std::size_t i = 0; i < result.steps.size(); ++i)
    result.steps[i].on_stairs =
        !std::isfinite(heights[i]) || std::abs(heights[i] - result.walking_height) > tolerance;
  result.on_storeys =
      summariseSteps(result.steps, [](const RegistrationStep& s) { return !s.on_stairs; });
  result.on_stairs =
      summariseSteps(result.steps, [](const RegistrationStep& s) { return s.on_stairs; });
}

RegistrationBiasResult measureRegistrationBias(LogReader& log, const Trajectory& truth,
                                               const OdometryConfig& odo,
                                               const RegistrationBiasOptions& options) {
  if (!(options.to >= options.from))
    throw Error("registration bias: --to (" + std::to_string(options.to) +
                " s) is before --from (" + std::to_string(options.from) + " s)");
  options.truth.validate();
  VoxelMap plane_map(odo.local_map), edge_map(odo.local_map);
  // The odometry inserts a scan into its map when it leaves the window, so
  // the newest window_size - 1 scans are not in the map yet.
  const std::size_t lag = static_cast<std::size_t>(std::max(odo.window_size, 2) - 1);
  struct Pending {
    std::vector<Eigen::Vector3f> planes_world;
    Eigen::Vector3d sensor_world;
  };
  std::vector<Pending> pending;
  Eigen::Vector3d last_trim(std::numeric_limits<double>::infinity(), 0.0, 0.0);

  RegistrationBiasResult result;
  std::optional<double> first_stamp;
  LogMessage message;
  while (log.next(message)) {
    const Scan* scan = std::get_if<Scan>(&message);
    if (!scan || scan->points.empty()) continue;
    ++result.scans_read;
    const double stamp = nsToSeconds(scan->stamp_ns);
    if (!first_stamp) first_stamp = stamp;
    const double since_start = stamp - *first_stamp;
    if (since_start > options.to) break;
    Pose T_world_lidar;
    const std::optional<Scan> deskewed = deskewWithTruth(
        *scan, truth, options.imu_truth, options.T_imu_lidar, options.truth, T_world_lidar);
    if (!deskewed) {
      ++result.scans_without_truth;
      continue;
    }
    const FeatureSet features = extractFeatures(*deskewed, odo.features);
    if (since_start >= options.from) {
      if (plane_map.empty()) {
        ++result.scans_without_map;
      } else {
        std::vector<Eigen::Vector3d> planes_lidar;
        planes_lidar.reserve(features.planes.size());
        for (const Eigen::Vector3f& p : features.planes) planes_lidar.push_back(p.cast<double>());
        const MatchResult matches = matchFeatures(planes_lidar, {}, T_world_lidar, plane_map,
                                                  edge_map, odo, Eigen::Vector3d::Zero());
        RegistrationStep step = stepAtPose(matches, T_world_lidar, odo.huber_threshold);
        step.time = stamp;
        step.since_start = since_start;
        step.position_true = T_world_lidar.translation();
        result.steps.push_back(step);
      }
    }
    Pending entry{{}, T_world_lidar.translation()};
    entry.planes_world.reserve(features.planes.size());
    for (const Eigen::Vector3f& p : features.planes)
      entry.planes_world.push_back((T_world_lidar * p.cast<double>()).cast<float>());
    pending.push_back(std::move(entry));
    if (pending.size() > lag) {
      plane_map.insert(pending.front().planes_world, pending.front().sensor_world);
      if ((pending.front().sensor_world - last_trim).norm() > 1.0) {
        plane_map.removeFar(pending.front().sensor_world);
        last_trim = pending.front().sensor_world;
      }
      pending.erase(pending.begin());
    }
  }
  if (result.steps.empty()) {
    std::ostringstream os;
    os << "registration bias: no scan of the log between " << options.from << " and " << options.to
       << " s after its start has a true pose (" << result.scans_read << " scans read, "
       << result.scans_without_truth
       << " outside the ground truth or in one of its gaps); do the truth's stamps use the "
          "log's clock?";
    throw Error(os.str());
  }
  summarise(result);
  stairsSplit(result, options.floor_elevations, options.storey_height_tolerance);
  return result;
}

void writeRegistrationBiasCsv(const std::string& path, const RegistrationBiasResult& result) {
  writeFileAtomically(path, [&](std::ostream& os) {
    os << "time,since_start,x_true,y_true,z_true,matches,floor_like,wall,slanted,ceiling_like,"
          "dx,dy,dz,dtheta_x,dtheta_y,dtheta_z,dz_floor_like,dz_wall,dz_slanted,dz_ceiling_like,"
          "on_stairs\n";
    char line[512];
    for (const RegistrationStep& s : result.steps) {
      std::snprintf(
          line, sizeof(line),
          "%.6f,%.3f,%.4f,%.4f,%.4f,%d,%d,%d,%d,%d,%.5f,%.5f,%.5f,%.6f,%.6f,%.6f,%.5f,%.5f,"
          "%.5f,%.5f,%s\n",
          s.time, s.since_start, s.position_true.x(), s.position_true.y(), s.position_true.z(),
          s.matches, s.class_matches[0], s.class_matches[1], s.class_matches[2], s.class_matches[3],
          s.dp.x(), s.dp.y(), s.dp.z(), s.dtheta.x(), s.dtheta.y(), s.dtheta.z(), s.class_dz[0],
          s.class_dz[1], s.class_dz[2], s.class_dz[3],
          result.split ? (s.on_stairs ? "1" : "0") : "");
      os << line;
    }
  });
}

std::string registrationBiasTable(const RegistrationBiasResult& r) {
  std::ostringstream os;
  char line[256];
  os << "Registration step at the true pose (map from the true poses)\n";
  std::snprintf(line, sizeof(line),
                "  scans evaluated %zu (read %zu, without truth %zu, before the map %zu)\n",
                r.steps.size(), r.scans_read, r.scans_without_truth, r.scans_without_map);
  os << line;
  std::snprintf(line, sizeof(line), "  mean step dx dy dz        %+.4f %+.4f %+.4f m\n",
                r.mean_dp.x(), r.mean_dp.y(), r.mean_dp.z());
  os << line;
  std::snprintf(line, sizeof(line), "  median |dz|, p95 |dp|     %.4f m, %.4f m\n", r.median_abs_dz,
                r.p95_abs_dp);
  os << line;
  os << "  mean dz by matched plane ";
  for (std::size_t c = 0; c < kPlaneClasses; ++c) {
    std::snprintf(line, sizeof(line), " %s %+.4f", toString(static_cast<PlaneClass>(c)),
                  r.class_mean_dz[c]);
    os << line;
  }
  os << " m\n";
  if (r.split) {
    std::snprintf(line, sizeof(line),
                  "  split by the true storeys (LiDAR usually %.2f m above its floor):\n",
                  r.walking_height);
    os << line;
    const auto group = [&](const char* name, const BiasSummary& b) {
      std::snprintf(line, sizeof(line),
                    "    %-11s %5zu scans, mean dz %+.4f m, median |dz| %.4f m, by plane", name,
                    b.scans, b.mean_dp.z(), b.median_abs_dz);
      os << line;
      for (std::size_t c = 0; c < kPlaneClasses; ++c) {
        std::snprintf(line, sizeof(line), " %+.4f", b.class_mean_dz[c]);
        os << line;
      }
      os << " m\n";
    };
    group("on storeys", r.on_storeys);
    group("on stairs", r.on_stairs);
  }
  os << "  one-second windows with the largest mean dz (start s, true z m, mean dz m, "
        "scans):\n";
  for (const BiasWindow& w : r.worst_windows) {
    std::snprintf(line, sizeof(line), "    %9.1f %8.2f %+8.4f %4d\n", w.since_start, w.z_true,
                  w.mean_dz, w.scans);
    os << line;
  }
  return os.str();
}

}  // namespace storey::eval
