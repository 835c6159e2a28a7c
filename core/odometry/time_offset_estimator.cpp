#include "odometry/time_offset_estimator.h"

#include <algorithm>
#include <cmath>

#include "imu/so3.h"

namespace storey {
namespace {

// Pairs whose rotation residual is beyond this are registration failures,
// not a time offset (a change of rate of 2 rad/s across a scan interval, a
// fast turn, with 20 ms of offset gives 0.04 rad) [rad].
constexpr double kMaxResidual = 0.05;
constexpr double kHuber = 1.345;  // in standard deviations
constexpr int kMinPairs = 50;
constexpr double kMinExcitation = 0.02;  // RMS |a| [rad/s]: the rate must change

}  // namespace

bool TimeOffsetEstimator::add(const Eigen::Quaterniond& dR_lidar, const Eigen::Quaterniond& dR_imu,
                              const Eigen::Vector3d& w_i, const Eigen::Vector3d& w_j) {
  const Eigen::Vector3d r = so3::logQuaternion(dR_imu.conjugate() * dR_lidar);
  const Eigen::Vector3d a = w_j - dR_imu.conjugate() * w_i;
  if (!r.allFinite() || !a.allFinite() || r.norm() > kMaxResidual) return false;
  pairs_.push_back({a.cast<float>(), r.cast<float>()});
  return true;
}

TimeOffsetEstimate TimeOffsetEstimator::estimate() const {
  TimeOffsetEstimate out;
  out.pairs = static_cast<int>(pairs_.size());
  if (out.pairs < kMinPairs) return out;
  double aa = 0.0;
  for (const Pair& p : pairs_) aa += p.a.cast<double>().squaredNorm();
  out.excitation = std::sqrt(aa / out.pairs);
  if (out.excitation < kMinExcitation) return out;
  // Iteratively reweighted least squares (Huber) of r = a delta + c + noise,
  // c the constant a gyro bias error leaves.
  double delta = 0.0, sigma = 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  std::vector<double> weights(pairs_.size(), 1.0);
  for (int iteration = 0; iteration < 8; ++iteration) {
    // Normal equations of [delta, c] (4 unknowns).
    Eigen::Matrix4d N = Eigen::Matrix4d::Zero();
    Eigen::Vector4d b = Eigen::Vector4d::Zero();
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      Eigen::Matrix<double, 3, 4> J;
      J << pairs_[k].a.cast<double>(), Eigen::Matrix3d::Identity();
      N += weights[k] * J.transpose() * J;
      b += weights[k] * J.transpose() * pairs_[k].r.cast<double>();
    }
    const Eigen::Vector4d x = N.ldlt().solve(b);
    delta = x(0);
    c = x.tail<3>();
    // Residual scale (per axis, robust: 1.4826 x the median absolute residual).
    std::vector<double> norms(pairs_.size());
    for (std::size_t k = 0; k < pairs_.size(); ++k)
      norms[k] = (pairs_[k].r.cast<double>() - pairs_[k].a.cast<double>() * delta - c).norm();
    std::vector<double> sorted = norms;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    // |residual| of 3 axes: its median is about 1.54 sigma for Gaussian axes.
    sigma = std::max(sorted[sorted.size() / 2] / 1.54, 1e-9);
    for (std::size_t k = 0; k < pairs_.size(); ++k)
      weights[k] = norms[k] <= kHuber * sigma ? 1.0 : kHuber * sigma / norms[k];
    if (iteration == 7) {
      const Eigen::Matrix4d covariance = N.inverse() * sigma * sigma;
      out.sigma_s = std::sqrt(std::max(covariance(0, 0), 0.0));
    }
  }
  out.offset_s = delta;
  return out;
}

}  // namespace storey
