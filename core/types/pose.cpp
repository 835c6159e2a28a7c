#include "types/pose.h"

#include <cmath>
#include <sstream>

#include "common/error.h"

namespace storey {

Eigen::Quaterniond normalizedQuaternion(const Eigen::Quaterniond& q) {
  const double norm = q.norm();
  if (!std::isfinite(norm) || norm < 1e-12) {
    std::ostringstream os;
    os << "quaternion (x y z w) = (" << q.x() << " " << q.y() << " " << q.z() << " " << q.w()
       << ") cannot be normalised";
    throw Error(os.str());
  }
  Eigen::Quaterniond unit(q.coeffs() / norm);
  if (unit.w() < 0.0) unit.coeffs() = -unit.coeffs();
  return unit;
}

Pose::Pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t)
    : q_(normalizedQuaternion(q)), t_(t) {
  if (!t_.allFinite()) throw Error("pose translation is not finite");
}

Pose::Pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) : Pose(Eigen::Quaterniond(R), t) {}

Pose Pose::fromIsometry(const Eigen::Isometry3d& T) {
  return Pose(Eigen::Matrix3d(T.linear()), Eigen::Vector3d(T.translation()));
}

Eigen::Isometry3d Pose::isometry() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q_.toRotationMatrix();
  T.translation() = t_;
  return T;
}

Pose Pose::operator*(const Pose& T_b_a) const {
  return Pose(q_ * T_b_a.q_, q_ * T_b_a.t_ + t_);
}

Pose Pose::inverse() const {
  const Eigen::Quaterniond q_inv = q_.conjugate();
  return Pose(q_inv, -(q_inv * t_));
}

double Pose::angle() const { return 2.0 * std::atan2(q_.vec().norm(), std::abs(q_.w())); }

bool Pose::isApprox(const Pose& other, double tol_translation, double tol_angle) const {
  const Pose delta = inverse() * other;
  return delta.translation().norm() <= tol_translation && delta.angle() <= tol_angle;
}

}  // namespace storey
