#pragma once
/// The IMU signal between two times (usually two scan times, which fall
/// between IMU samples), as a piecewise-linear function of time: the samples
/// strictly inside the interval plus a value linearly interpolated at each
/// end. Preintegration and pose propagation both integrate this signal, so
/// they agree exactly.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "types/imu_sample.h"

namespace storey {

/// One knot of the piecewise-linear IMU signal.
struct ImuKnot {
  double t = 0.0;                                   ///< time since ImuSignal::start_ns [s]
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< angular rate, IMU frame [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< specific force, IMU frame [m/s^2]
  /// Spacing of the two IMU samples between which the interval from the
  /// previous knot to this one lies (that interval's length unless an end
  /// was interpolated; 0 for the first knot) [s]: a dropout when long.
  double sample_spacing = 0.0;
  /// The interval is a dropout whatever sample_spacing: samples before its
  /// end were removed (ImuSample::after_removed), or an end is not measured
  /// but filled in (ImuSample::filled).
  bool dropout = false;
};

struct ImuSignal {
  std::int64_t start_ns = 0;   ///< first knot's time [ns]
  std::int64_t end_ns = 0;     ///< last knot's time [ns]
  std::vector<ImuKnot> knots;  ///< >= 2 knots, strictly increasing t, knots.front().t == 0
  double max_gap = 0.0;        ///< longest interval between two knots [s] (dropouts)
  double duration() const { return knots.empty() ? 0.0 : knots.back().t; }  ///< [s]
};

/// Cuts [start_ns, end_ns] out of time-ordered samples. Needs a sample at or
/// before start_ns and one at or after end_ns; samples with the same stamp as
/// the previous one are skipped. Throws storey::Error when start_ns >= end_ns,
/// when the samples do not cover the interval, go back in time, or are not
/// finite inside it. Cost: O(log n + samples inside).
ImuSignal sliceImuSignal(const ImuSample* samples, std::size_t count, std::int64_t start_ns,
                         std::int64_t end_ns);
inline ImuSignal sliceImuSignal(const std::vector<ImuSample>& samples, std::int64_t start_ns,
                                std::int64_t end_ns) {
  return sliceImuSignal(samples.data(), samples.size(), start_ns, end_ns);
}

}  // namespace storey
