#pragma once
/// SO(3) helpers for rotation vectors (axis * angle [rad]): exponential and
/// logarithm maps and the right Jacobian, as used by IMU preintegration
/// (Forster et al., TRO 2017, eqs. 1-8).
///
/// Conventions: Exp(phi) is the rotation by |phi| rad about phi/|phi|;
/// Jr(phi) is the right Jacobian, Exp(phi + d) ~= Exp(phi) Exp(Jr(phi) d), and
/// Log(Exp(phi) Exp(d)) ~= phi + Jr^-1(phi) d. Quaternions are Hamilton
/// (Eigen::Quaterniond). Small angles use Taylor series, so every function is
/// accurate to double precision down to phi = 0.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace storey {
namespace so3 {

/// [v]x: skew-symmetric matrix with skew(a) * b = a.cross(b).
inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return m;
}

/// Below this angle [rad] the closed forms are replaced by Taylor series
/// (truncation error < angle^6 / 40320 < 3e-17).
constexpr double kSmallAngle = 1e-2;

/// Exp(phi) as a unit quaternion.
inline Eigen::Quaterniond expQuaternion(const Eigen::Vector3d& phi) {
  const double theta2 = phi.squaredNorm();
  double w, k;  // q = (w, k * phi)
  if (theta2 < kSmallAngle * kSmallAngle) {
    w = 1.0 - theta2 / 8.0 + theta2 * theta2 / 384.0;
    k = 0.5 - theta2 / 48.0 + theta2 * theta2 / 3840.0;
  } else {
    const double theta = std::sqrt(theta2);
    w = std::cos(0.5 * theta);
    k = std::sin(0.5 * theta) / theta;
  }
  Eigen::Quaterniond q(w, k * phi.x(), k * phi.y(), k * phi.z());
  q.normalize();
  return q;
}

/// Exp(phi) as a rotation matrix.
inline Eigen::Matrix3d expMatrix(const Eigen::Vector3d& phi) {
  return expQuaternion(phi).toRotationMatrix();
}

/// Log(q): rotation vector with angle in [0, pi]; q need not have w >= 0.
inline Eigen::Vector3d logQuaternion(const Eigen::Quaterniond& q_in) {
  const double sign = q_in.w() < 0.0 ? -1.0 : 1.0;
  const double w = sign * q_in.w();
  const Eigen::Vector3d v = sign * q_in.vec();
  const double n = v.norm();
  if (n < 1e-6 * w) {
    // angle = 2 atan(n / w) = 2 (n/w) (1 - (n/w)^2 / 3 + ...)
    const double r2 = (n * n) / (w * w);
    return (2.0 / w) * (1.0 - r2 / 3.0) * v;
  }
  return (2.0 * std::atan2(n, w) / n) * v;
}

/// Log(R) of a rotation matrix.
inline Eigen::Vector3d logMatrix(const Eigen::Matrix3d& R) {
  return logQuaternion(Eigen::Quaterniond(R));
}

/// Right Jacobian Jr(phi) = I - (1 - cos t)/t^2 [phi]x + (t - sin t)/t^3 [phi]x^2, t = |phi|.
inline Eigen::Matrix3d rightJacobian(const Eigen::Vector3d& phi) {
  const double t2 = phi.squaredNorm();
  double a, b;
  if (t2 < kSmallAngle * kSmallAngle) {
    a = 0.5 - t2 / 24.0 + t2 * t2 / 720.0;
    b = 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0;
  } else {
    const double t = std::sqrt(t2);
    a = (1.0 - std::cos(t)) / t2;
    b = (t - std::sin(t)) / (t2 * t);
  }
  const Eigen::Matrix3d K = skew(phi);
  return Eigen::Matrix3d::Identity() - a * K + b * K * K;
}

/// Inverse right Jacobian Jr^-1(phi) = I + 1/2 [phi]x + (1/t^2 - (1 + cos t)/(2 t sin t)) [phi]x^2.
/// Valid for |phi| < pi (the angle of any Log).
inline Eigen::Matrix3d rightJacobianInverse(const Eigen::Vector3d& phi) {
  const double t2 = phi.squaredNorm();
  double c;
  if (t2 < kSmallAngle * kSmallAngle) {
    c = 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0;
  } else {
    const double t = std::sqrt(t2);
    c = 1.0 / t2 - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t));
  }
  const Eigen::Matrix3d K = skew(phi);
  return Eigen::Matrix3d::Identity() + 0.5 * K + c * K * K;
}

}  // namespace so3
}  // namespace storey
