#pragma once
/// Detects and estimates a constant time offset between the IMU and the
/// LiDAR clocks that the calibration does not know
/// (docs/method/odometry.md, "IMU-LiDAR time offset").
///
/// If the IMU sample at IMU time t + offset + delta, not t + offset, is the
/// one measured with the LiDAR's time t (offset: the configured
/// sensor.time_offset_lidar_to_imu), the gyro integrated over a scan
/// interval [t_i, t_j] (IMU clock, configured offset) is the rotation of the
/// interval shifted by -delta:
///   dR_true = Exp(w_i (-delta))^T dR_imu Exp(w_j (-delta))   (body rates w)
/// so, to first order in delta, the rotation the LiDAR measures differs from
/// the gyro's by
///   r = Log(dR_imu^T dR_lidar) ~= (w_j - dR_imu^T w_i) delta = a delta.
/// Each pair of consecutive scans gives (a, r); delta is their robust
/// (Huber, IRLS) least-squares slope, with its standard deviation from the
/// residuals. Rotation changes carry the signal (|a|: the change of the
/// rotation rate across a scan interval), so a log without turns has no
/// estimate. The gyro bias error adds a constant to r, which turns do not
/// correlate with.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace storey {

struct TimeOffsetEstimate {
  int pairs = 0;            ///< scan pairs used
  double offset_s = 0.0;    ///< delta: add it to the configured offset [s]
  double sigma_s = 0.0;     ///< standard deviation of delta [s]; 0 without an estimate
  double excitation = 0.0;  ///< RMS |a| over the pairs [rad/s]
  bool valid() const { return sigma_s > 0.0; }
  /// An offset the log shows: at least 1 ms and 3 standard deviations (the
  /// clean simulated walks show 0.0-0.7 ms within 1.3 sigma).
  bool detected() const {
    return valid() && std::abs(offset_s) >= 0.001 && std::abs(offset_s) >= 3.0 * sigma_s;
  }
};

class TimeOffsetEstimator {
 public:
  /// One pair of consecutive scans i, j: the LiDAR's relative rotation
  /// R_i^T R_j, the gyro's over the same interval (bias-corrected), and the
  /// bias-corrected body rates at both ends [rad/s]. False when the pair
  /// is left out (not finite, or a residual no time offset explains).
  bool add(const Eigen::Quaterniond& dR_lidar, const Eigen::Quaterniond& dR_imu,
           const Eigen::Vector3d& w_i, const Eigen::Vector3d& w_j);
  TimeOffsetEstimate estimate() const;
  std::size_t pairs() const { return pairs_.size(); }

 private:
  struct Pair {
    Eigen::Vector3f a, r;
  };
  std::vector<Pair> pairs_;
};

}  // namespace storey
