#pragma once
/// Registration bias against the truth: how far the odometry's LiDAR
/// registration would move a scan that is already at its TRUE pose, matched
/// against a local map built from the TRUE poses of the scans before it.
///
/// Each scan of the log is deskewed with the true trajectory, its planar
/// features are extracted and matched exactly as the odometry does
/// (odometry/scan_matcher.h, same configuration), and the Gauss-Newton step
/// of the point-to-plane cost (Huber weights as in the odometry) is computed
/// at the true pose. A perfect measurement model gives a step of zero up to
/// noise; a mean step over a stretch of the walk is a bias that the odometry
/// will follow there (docs/evaluation.md, docs/method/odometry.md). The step
/// is also split by the orientation of the matched plane, so a bias can be
/// traced to floors, walls, ceilings or slanted fits.
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "eval/association.h"
#include "odometry/odometry_config.h"
#include "trajectory/tum.h"

namespace storey {
class LogReader;
}

namespace storey::eval {

/// Orientation classes of a matched map plane (world frame, z up).
enum class PlaneClass { kFloorLike = 0, kWall, kSlanted, kCeilingLike, kCount };
const char* toString(PlaneClass c);
constexpr std::size_t kPlaneClasses = static_cast<std::size_t>(PlaneClass::kCount);

struct RegistrationBiasOptions {
  double from = 0.0;  ///< first scan evaluated, seconds after the first scan of the log
  double to = std::numeric_limits<double>::infinity();  ///< last one, same clock [s]
  AssociationOptions truth;  ///< how the truth is looked up at a time (as `storey eval` does)
  /// Optional, not owned: the IMU's true trajectory (T_world_imu, e.g. the
  /// simulator's groundtruth_imu.tum at the IMU's rate). With it every point
  /// is deskewed with its own true pose, T_world_imu(t) T_imu_lidar, and the
  /// scans' poses come from it too; without it the LiDAR truth (one pose a
  /// scan) is interpolated within each revolution, which on a hand-held walk
  /// is off by a few mrad (median 2.4, up to 17 mrad on development seed 9).
  const Trajectory* imu_truth = nullptr;
  Pose T_imu_lidar;  ///< with imu_truth: the LiDAR's pose in the IMU frame
  /// True floor elevations of the storeys (world z, top of the slab [m], e.g.
  /// the simulator's storeys.yaml); with them the steps are also summarised
  /// apart for the scans on a storey and on the stairs (stairsSplit()). Empty: no split.
  std::vector<double> floor_elevations;
  /// A scan is on a storey when the LiDAR's height above the floor below it is
  /// within this of the walk's usual height above its floor [m].
  double storey_height_tolerance = 0.15;
};

/// One scan: the step from its true pose.
struct RegistrationStep {
  double time = 0.0;         ///< scan stamp [s]
  double since_start = 0.0;  ///< seconds after the first scan of the log
  Eigen::Vector3d position_true = Eigen::Vector3d::Zero();  ///< LiDAR, world [m]
  int matches = 0;                                          ///< point-to-plane matches
  std::array<int, kPlaneClasses> class_matches{};           ///< per PlaneClass
  Eigen::Vector3d dp = Eigen::Vector3d::Zero();             ///< translation step, world [m]
  Eigen::Vector3d dtheta = Eigen::Vector3d::Zero();         ///< rotation step, world [rad]
  std::array<double, kPlaneClasses> class_dz{};  ///< z of the step each class alone would cause [m]
  bool on_stairs = false;                        ///< between storeys (only with floor elevations)
};

/// The steps of a set of scans in a few numbers.
struct BiasSummary {
  std::size_t scans = 0;
  Eigen::Vector3d mean_dp = Eigen::Vector3d::Zero();  ///< [m]
  double median_abs_dz = 0.0;                         ///< [m]
  double p95_abs_dp = 0.0;                            ///< 95th percentile of |dp| [m]
  std::array<double, kPlaneClasses> class_mean_dz{};  ///< mean of class_dz per class [m]
};

/// A one-second stretch with a large mean vertical step.
struct BiasWindow {
  double since_start = 0.0;  ///< start, seconds after the first scan
  double z_true = 0.0;       ///< true LiDAR height at its start [m]
  double mean_dz = 0.0;      ///< mean vertical step of its scans [m]
  int scans = 0;
};

struct RegistrationBiasResult {
  std::vector<RegistrationStep> steps;                ///< every evaluated scan, in log order
  std::size_t scans_read = 0;                         ///< scans in the log
  std::size_t scans_without_truth = 0;                ///< outside the truth or in one of its gaps
  std::size_t scans_without_map = 0;                  ///< too early: the map was still empty
  Eigen::Vector3d mean_dp = Eigen::Vector3d::Zero();  ///< over `steps` [m]
  double median_abs_dz = 0.0;                         ///< [m]
  double p95_abs_dp = 0.0;                            ///< 95th percentile of |dp| [m]
  std::array<double, kPlaneClasses> class_mean_dz{};  ///< mean of class_dz per class [m]
  std::vector<BiasWindow> worst_windows;  ///< up to 5 one-second windows, largest |mean_dz| first
  /// With floor elevations: the split of the steps (RegistrationStep::on_stairs).
  bool split = false;
  double walking_height = 0.0;  ///< median LiDAR height above the floor below it [m]
  BiasSummary on_storeys, on_stairs;
};

/// The LiDAR's height above the highest of `floor_elevations` below
/// `z_lidar` (sorted or not); NaN when no floor is below it [m].
double heightAboveFloor(double z_lidar, const std::vector<double>& floor_elevations);

/// Marks every step on_stairs or not and fills result.split, walking_height,
/// on_storeys and on_stairs: the walk's usual height above its floor is the
/// median of heightAboveFloor over the steps (a walk spends most of its time
/// on storeys); a step whose height differs from it by more than
/// `tolerance`, or that has no floor below it, is on the stairs (flights,
/// half landings). Nothing happens without floors.
void stairsSplit(RegistrationBiasResult& result, const std::vector<double>& floor_elevations,
                 double tolerance);

/// Runs the measurement over a log. `truth` is the LiDAR's true trajectory
/// (T_world_lidar, TUM, e.g. the simulator's groundtruth_lidar.tum). Throws
/// storey::Error when the truth covers no evaluated scan.
RegistrationBiasResult measureRegistrationBias(LogReader& log, const Trajectory& truth,
                                               const OdometryConfig& odometry,
                                               const RegistrationBiasOptions& options = {});

/// The per-scan table as CSV (header line first), written atomically.
void writeRegistrationBiasCsv(const std::string& path, const RegistrationBiasResult& result);

/// Human-readable summary (the numbers of RegistrationBiasResult).
std::string registrationBiasTable(const RegistrationBiasResult& result);

}  // namespace storey::eval
