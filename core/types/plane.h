#pragma once
/// Plane in Hesse normal form: n . x = d with |n| = 1 and d >= 0 (n is flipped
/// when d < 0; for d == 0 the sign of n is kept). Frame named by the variable
/// (plane_world, plane_keyframe).
#include <Eigen/Core>

#include "types/pose.h"

namespace storey {

class Plane {
 public:
  Plane() : n_(Eigen::Vector3d::UnitZ()), d_(0.0) {}
  /// Normalises n (throws storey::Error on a zero or non-finite normal) and
  /// applies the sign convention d >= 0.
  Plane(const Eigen::Vector3d& n, double d);

  const Eigen::Vector3d& normal() const { return n_; }
  double distance() const { return d_; }
  /// Signed distance of a point from the plane (positive on the side n points to).
  double signedDistance(const Eigen::Vector3d& x) const { return n_.dot(x) - d_; }
  /// The same plane expressed in frame b, given the plane in frame a and T_b_a:
  /// n_b = R n_a, d_b = d_a + n_b . t.
  Plane transformed(const Pose& T_b_a) const;
  /// Angle (rad) between the normals and |d difference| (m).
  double angleTo(const Plane& other) const;

 private:
  Eigen::Vector3d n_;
  double d_;
};

}  // namespace storey
