#pragma once
/// Initialisation while moving (docs/method/odometry.md, "Starting in
/// motion"): when a log does not start at rest, gravity's direction, the
/// velocity and the IMU biases are estimated from the first seconds of LiDAR
/// and IMU data together, in the manner of the visual-/LiDAR-inertial
/// alignments of VINS-Mono and LI-Init:
///
/// 1. LiDAR-only registration of the window's scans in a provisional world
///    frame W' (levelled by the mean specific force over the window, rotated
///    into one frame with the gyro). First pass: each scan deskewed with the
///    IMU from its guessed state (gyro rotation, constant velocity), then
///    registered to the scans before it, pose only, with a weak prior at the
///    guess so that a degenerate corridor does not slide. Second pass: every
///    scan deskewed with the first pass' states and registered to the map of
///    all the others (a map of one scan carries that scan's noise in its
///    plane fits, and every scan after it inherits the error).
/// 2. Gyro bias: the registered rotations R_0^T R_k against the
///    preintegrated rotations dR_0k(bg), linearised in bg
///    (dR_0k(bg) ~= dR_0k Exp(J_k dbg)), least squares over every k.
/// 3. Velocity, gravity and accelerometer bias from the registered IMU
///    positions, each an independent measurement (sigma 1 cm) of
///      p_k = c + v_0 T_k + g T_k^2 / 2 + R_0 (dp_0k + dp/dba b_a)
///    with T_k = t_k - t_0 and the deltas preintegrated from the first scan:
///    linear in [v_0, g, b_a, c], b_a with its prior (mean 0,
///    prior_accel_bias_sigma; it takes the part of |g| that is the bias along
///    gravity, as the still start does). |g| must come out within
///    max_gravity_error of the configured value (else the data do not fit:
///    an error); then |g| is fixed and its direction refined on its 2-D
///    tangent (g = |g| u + B w, four Gauss-Newton steps).
/// 4. The levelled frame W = R_lev W' (R_lev turns g to -z). The result is
///    the first scan's state, with the uncertainties of the solution for the
///    odometry's first prior, and the window's registered scans, which the
///    odometry takes as its first local map.
#include <cstdint>
#include <vector>

#include "imu/imu_config.h"
#include "imu/imu_state.h"
#include "odometry/odometry_config.h"
#include "types/imu_sample.h"
#include "types/pose.h"
#include "types/scan.h"
#include "types/sensor.h"

namespace storey {

/// What the initialisation saw and how sure it is (run report, first prior).
struct MotionInitStats {
  int scans = 0;                      ///< scans registered in the window
  double window_s = 0.0;              ///< first to last scan [s]
  double gravity_norm = 0.0;          ///< |g| before fixing it to the configured value [m/s^2]
  double speed_start = 0.0;           ///< |v| at the first scan [m/s]
  double vertical_speed_start = 0.0;  ///< v_z at the first scan [m/s]
  double path_length = 0.0;           ///< distance travelled in the window [m]
  double position_rms = 0.0;          ///< RMS residual of the position equations [m]
  int min_matches = 0;                ///< fewest plane + line matches of a registered scan
  double velocity_sigma = 0.0;        ///< std of v_0 (largest axis) [m/s]
  double tilt_sigma = 0.0;            ///< std of gravity's direction (largest axis) [rad]
  double gyro_bias_sigma = 0.0;       ///< std of the gyro bias (largest axis) [rad/s]
  double accel_bias_sigma = 0.0;      ///< std of the accelerometer bias (largest axis) [m/s^2]
};

/// One scan of the window as the initialisation registered it: the
/// odometry's local map starts from these (a map of the whole window, not
/// of its first scan alone).
struct MotionInitScan {
  std::int64_t state_ns = 0;  ///< the scan's reference time (IMU clock) [ns]
  Pose T_world_imu;           ///< registered pose, same frame as MotionInitResult::state
  std::vector<Eigen::Vector3d> planes_imu, edges_imu;  ///< features, IMU frame [m]
};

struct MotionInitResult {
  /// IMU state at the first scan's reference time (its stamp + the
  /// LiDAR-to-IMU time offset): gravity-aligned world (origin and yaw
  /// arbitrary: the odometry sets its own), velocity and both biases estimated.
  ImuState state;
  MotionInitStats stats;
  std::vector<MotionInitScan> scans;  ///< the window's scans, first = the state's
};

/// Initialises from `scans` (time order, reference times inside the IMU
/// data, at least ImuInitConfig::motion_min_scans of them) and time-ordered
/// `imu` samples covering them. Throws storey::Error naming the reason when
/// the data do not allow it (too few scans or matches, gravity not found).
MotionInitResult initializeInMotion(const std::vector<ImuSample>& imu,
                                    const std::vector<const Scan*>& scans,
                                    const OdometryConfig& config, const SensorConfig& sensor);

}  // namespace storey
