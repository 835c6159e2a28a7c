#pragma once
/// IMU state propagation for deskewing: the world pose of the IMU at any time
/// of an interval, from a start state and the IMU signal.
///
/// Construction integrates the signal in the world frame with the same
/// trapezoidal scheme as ImuPreintegration (so the end state equals
/// ImuPreintegration::predict up to rounding) and stores R, p, v at every
/// knot. A query at time t inside knot interval [t_k, t_k+1] (tau = t - t_k,
/// h = t_k+1 - t_k, w = bias-corrected gyro, linear in time):
///   R(t) = R_k Exp(w_k tau + (w_k+1 - w_k) tau^2 / (2 h))   (Exp to 4th order)
///   p(t) = cubic Hermite through (p_k, v_k) and (p_k+1, v_k+1)
/// so it is O(1) (an index guess from the mean knot spacing, then a short
/// walk), thread-safe (const, no cache) and exact at the knots. Outside
/// [0, duration] the pose is extrapolated with the end's velocity and angular
/// rate (constant-velocity model).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "imu/imu_signal.h"
#include "imu/imu_state.h"
#include "types/pose.h"

namespace storey {

class ImuPoseTable {
 public:
  /// start.stamp_ns must equal signal.start_ns (throws storey::Error otherwise);
  /// start.bias is used for the whole interval. gravity: magnitude [m/s^2].
  ImuPoseTable(const ImuState& start, ImuSignal signal, double gravity);
  /// Shorthand: slices [start.stamp_ns, end_ns] out of `samples` and builds the table.
  static ImuPoseTable fromSamples(const ImuState& start, const std::vector<ImuSample>& samples,
                                  std::int64_t end_ns, double gravity);

  /// Rotation and position of the IMU in the world at time t [s] since
  /// startNs(). About 45 ns.
  void interpolate(double t, Eigen::Quaterniond& q_world_imu, Eigen::Vector3d& p_world_imu) const;
  /// Same as interpolate, as a Pose.
  Pose T_world_imu(double t) const;
  /// Full state (pose, velocity, biases) at time t [s] since startNs(); stamp rounded to ns.
  ImuState stateAt(double t) const;
  /// State at the end of the interval.
  ImuState endState() const { return stateAtKnot(knots_.size() - 1); }

  std::int64_t startNs() const { return start_ns_; }   ///< [ns]
  std::int64_t endNs() const { return end_ns_; }       ///< [ns]
  double duration() const { return knots_.back().t; }  ///< [s]
  /// Seconds from startNs() to stamp_ns + offset_s (e.g. a scan stamp and a point's time).
  double secondsSinceStart(std::int64_t stamp_ns, double offset_s = 0.0) const {
    return nsToSeconds(stamp_ns - start_ns_) + offset_s;
  }

 private:
  struct Knot {
    double t;              // [s] since start
    Eigen::Quaterniond q;  // q_world_imu
    Eigen::Vector3d p;     // p_world_imu [m]
    Eigen::Vector3d v;     // v_world_imu [m/s]
    Eigen::Vector3d w;     // bias-corrected angular rate at the knot [rad/s]
  };
  std::size_t intervalOf(double t) const;
  ImuState stateAtKnot(std::size_t k) const;

  std::int64_t start_ns_ = 0;
  std::int64_t end_ns_ = 0;
  ImuBias bias_;
  Eigen::Vector3d gravity_world_;
  double knots_per_second_ = 0.0;
  std::vector<Knot> knots_;
};

}  // namespace storey
