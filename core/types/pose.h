#pragma once
/// Rigid transform (rotation + translation). Convention: a pose named T_b_a maps
/// points expressed in frame a into frame b: x_b = T_b_a * x_a = R * x_a + t.
/// Rotations are Hamilton unit quaternions (Eigen::Quaterniond); the constructor
/// normalises and rejects quaternions that cannot be normalised.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace storey {

class Pose {
 public:
  Pose() : q_(Eigen::Quaterniond::Identity()), t_(Eigen::Vector3d::Zero()) {}
  /// Throws storey::Error if q has (near) zero norm or is not finite.
  Pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t);
  Pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t);
  static Pose identity() { return Pose(); }
  static Pose fromIsometry(const Eigen::Isometry3d& T);

  const Eigen::Quaterniond& rotation() const { return q_; }
  Eigen::Matrix3d rotationMatrix() const { return q_.toRotationMatrix(); }
  const Eigen::Vector3d& translation() const { return t_; }
  Eigen::Isometry3d isometry() const;
  Eigen::Matrix4d matrix() const { return isometry().matrix(); }

  /// T_c_a = T_c_b * T_b_a
  Pose operator*(const Pose& T_b_a) const;
  /// x_b = T_b_a * x_a
  Eigen::Vector3d operator*(const Eigen::Vector3d& x_a) const { return q_ * x_a + t_; }
  Pose inverse() const;

  /// Rotation angle (rad) and translation norm (m) of this pose; used to compare poses.
  double angle() const;
  bool isApprox(const Pose& other, double tol_translation = 1e-9, double tol_angle = 1e-9) const;

 private:
  Eigen::Quaterniond q_;
  Eigen::Vector3d t_;
};

/// Normalises q to unit norm with non-negative w (the same rotation). Throws
/// storey::Error when q is not finite or its norm is below 1e-12.
Eigen::Quaterniond normalizedQuaternion(const Eigen::Quaterniond& q);

}  // namespace storey
