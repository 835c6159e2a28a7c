#include "types/plane.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace storey {

Plane::Plane(const Eigen::Vector3d& n, double d) {
  const double norm = n.norm();
  if (!std::isfinite(norm) || norm < 1e-12 || !std::isfinite(d))
    throw Error("plane normal must be a finite non-zero vector and d finite");
  n_ = n / norm;
  d_ = d / norm;
  if (d_ < 0.0) {
    n_ = -n_;
    d_ = -d_;
  }
}

Plane Plane::transformed(const Pose& T_b_a) const {
  const Eigen::Vector3d n_b = T_b_a.rotation() * n_;
  return Plane(n_b, d_ + n_b.dot(T_b_a.translation()));
}

double Plane::angleTo(const Plane& other) const {
  return std::acos(std::clamp(n_.dot(other.n_), -1.0, 1.0));
}

}  // namespace storey
