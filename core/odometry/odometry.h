#pragma once
/// Tightly coupled LiDAR-inertial odometry (the front end; section IV of the
/// reference paper, docs/method/odometry.md).
///
/// Per scan: IMU preintegration from the previous state predicts the state at
/// the scan's reference time; the scan is deskewed with the IMU-propagated
/// motion; LOAM edge and planar features are extracted and associated with a
/// voxel-hash local map (point-to-line, point-to-plane); then the states of a
/// sliding window (pose, velocity, biases; the oldest held fixed) are solved
/// jointly with Ceres from the IMU factors between them and the LiDAR
/// residuals of their scans, robust and covariance-weighted. A scan leaves the
/// window with its final estimate: its features enter the local map and its
/// result is queued for nextResult(). The odometry knows nothing of the
/// stages after it (data flow one way: odometry -> back end).
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "imu/imu_preintegration.h"
#include "imu/imu_state.h"
#include "imu/imu_state_blocks.h"
#include "odometry/imu_gap_fill.h"
#include "odometry/motion_init.h"
#include "odometry/odometry_config.h"
#include "odometry/scan_matcher.h"
#include "odometry/time_offset_estimator.h"
#include "odometry/voxel_map.h"
#include "types/imu_sample.h"
#include "types/pose.h"
#include "types/scan.h"
#include "types/sensor.h"

namespace storey {

class ParallelChunks;

/// What happened to one scan (summed into the run report).
struct OdometryScanStats {
  std::int64_t points = 0;
  std::int64_t edge_features = 0;
  std::int64_t plane_features = 0;
  std::int64_t plane_matches = 0;
  std::int64_t line_matches = 0;
  std::array<std::int64_t, static_cast<std::size_t>(FeatureReject::kCount)> feature_rejects{};
  std::array<std::int64_t, static_cast<std::size_t>(MatchReject::kCount)> match_rejects{};
  int degenerate_translation_directions = 0;  ///< LiDAR-only std above the threshold
  int degenerate_rotation_directions = 0;
  double lidar_translation_std_max = 0.0;  ///< largest LiDAR-only std of translation [m]
  int solver_iterations = 0;
  // Wall-clock time of each stage for this scan [ms].
  double ms_preintegration = 0.0, ms_deskew = 0.0, ms_features = 0.0, ms_matching = 0.0,
         ms_optimisation = 0.0, ms_total = 0.0;
  double cpu_ms_total = 0.0;  ///< the odometry thread's CPU time for this scan [ms]
};

/// The odometry's estimate of one scan, final once it left the window.
struct OdometryResult {
  std::int64_t scan_stamp_ns = 0;  ///< the scan's header stamp (LiDAR clock) [ns]
  ImuState state;                  ///< IMU state at the scan's reference time (IMU clock)
  /// LiDAR pose at the reference time in the odometry's own map frame: the
  /// frame its local map is built in, rigid over the whole log. Its z axis is
  /// the still start's accelerometer-levelled vertical, off the true one by
  /// the accelerometer bias (|b| / |g|) until turns tell the two apart.
  Pose T_odom_lidar;
  /// The current levelling of that frame by the window's gravity estimate
  /// (world = q_world_odom odom, docs/method/odometry.md "Gravity's
  /// direction"). It changes as the estimate improves: poses levelled at
  /// different times are in different frames, so consumers that compose
  /// poses of different scans use T_odom_lidar and one levelling.
  Eigen::Quaterniond q_world_odom = Eigen::Quaterniond::Identity();
  Scan deskewed;  ///< the scan's points at the reference time, LiDAR frame
  OdometryScanStats stats;
};

/// How the odometry started (run report).
struct OdometryInitialisation {
  bool in_motion = false;  ///< initialised while moving (odometry/motion_init.h), not at rest
  std::string not_still;   ///< in_motion: why the start was not taken as still
  MotionInitStats motion;  ///< in_motion: what the in-motion initialisation saw
};

/// Why scans were not used (besides errors); counts in the run report.
struct OdometryDrops {
  std::int64_t before_first_imu = 0;  ///< scan earlier than the first IMU sample
  std::int64_t after_last_imu = 0;    ///< the IMU data end before the scan does (end of log)
  std::int64_t empty = 0;             ///< scan without points
};

class LidarInertialOdometry {
 public:
  LidarInertialOdometry(const OdometryConfig& config, const SensorConfig& sensor);
  ~LidarInertialOdometry();

  /// Feed the log in time order (IMU samples by stamp, scans by stamp +
  /// time offset); scans wait until the IMU covers them.
  void addImu(const ImuSample& sample);
  void addScan(Scan scan);
  /// End of the log: processes what the IMU covers and flushes the window.
  void finish();
  /// The oldest final result not taken yet (scans in time order, each once
  /// it left the window); false when there is none. Call after each add*()
  /// and after finish() until it returns false: results wait in a queue.
  bool nextResult(OdometryResult& result);

  const OdometryDrops& drops() const { return drops_; }
  bool initialised() const { return initialised_; }
  const ImuState& initialState() const { return initial_state_; }
  const OdometryInitialisation& initialisation() const { return initialisation_; }
  /// The IMU-LiDAR time offset beyond the configured one that the scans
  /// emitted so far show (time_offset_estimator.h).
  TimeOffsetEstimate timeOffset() const { return time_offset_.estimate(); }

 private:
  struct Frame;
  /// What a dropout after the newest sample is filled with (imu_gap_fill.h).
  ImuGapMotion continuedMotion() const;
  void tryProcess(bool at_end);
  /// Still start when there is one, else (once the data cover the motion
  /// window) in motion; false while waiting for more data.
  bool initialise(bool at_end);
  bool initialiseInMotion(bool at_end);
  void processScan(const Scan& scan);
  /// Inserts the in-motion initialisation's scans into the local map, the
  /// first at T_world_imu_first (the first frame's pose).
  void seedLocalMap(const Pose& T_world_imu_first);
  void optimise(Frame& newest);
  void slide();
  void emit(Frame& frame);  ///< queues the frame's final result
  /// Where the frame's LiDAR residuals alone put its rotation (one
  /// Gauss-Newton step from its final pose); false when its rotation is
  /// degenerate or it has few matches.
  bool lidarOnlyRotation(const Frame& frame, Eigen::Quaterniond& q_world_imu) const;
  void trimImu();

  OdometryConfig config_;
  SensorConfig sensor_;
  std::deque<OdometryResult> results_;  ///< final results not taken yet
  std::int64_t time_offset_ns_ = 0;
  std::vector<ImuSample> imu_;  ///< measured, and filled across dropouts
  std::deque<Scan> pending_;
  /// The last point time of pending_.front() past its stamp [ns], once computed
  /// (tryProcess runs for every IMU sample while the scan waits for them).
  std::optional<std::int64_t> front_span_ns_;
  bool initialised_ = false;
  bool origin_set_ = false;
  ImuState initial_state_;
  OdometryInitialisation initialisation_;
  bool still_failed_ = false;
  /// Started in motion: the window's registered scans, inserted into the
  /// local map with the first frame; then the reference times of those
  /// scans, whose frames are not inserted again.
  std::vector<MotionInitScan> seed_scans_;
  std::vector<std::int64_t> seeded_ns_;
  std::deque<std::unique_ptr<Frame>> window_;
  std::unique_ptr<ParallelChunks> parallel_;  ///< features and matching (config.threads)
  VoxelMap plane_map_;
  VoxelMap edge_map_;
  Eigen::Vector3d last_map_trim_position_ = Eigen::Vector3d::Zero();
  /// Tilt of gravity in the map frame (ImuGravityFactor): g = Exp([t, 0]) (0, 0, -|g|).
  double tilt_[2] = {0.0, 0.0};
  OdometryDrops drops_;
  TimeOffsetEstimator time_offset_;
  /// LiDAR-only rotation of the last emitted scan (for the time offset), if usable.
  bool last_rotation_valid_ = false;
  Eigen::Quaterniond last_lidar_rotation_ = Eigen::Quaterniond::Identity();
};

}  // namespace storey
