#pragma once
/// The odometry's tilt as a prior on every keyframe's attitude.
///
/// The odometry is tightly coupled with the IMU: its roll and pitch are
/// observed through gravity at every instant and do not drift, whereas its
/// relative poses (the graph's odometry edges) let the keyframes' tilt wander
/// by odometry_sigma_rotation per edge. Without an absolute tilt, plane
/// observations with correlated errors (one wrong fit seen by many keyframes)
/// can tilt a run of keyframes, and the tilt turns every relative
/// translation after it into height.
///
/// Residual (docs/method/backend.md, "Gravity"): with z = (0, 0, 1) the world's
/// up, R the keyframe's estimated attitude and R_ref = q_world_odom R_odom_kf
/// the odometry's own attitude levelled by its gravity estimate,
///   g = R^T z                (up in the keyframe frame, as estimated),
///   r = P R_ref g / sigma,   P = the first two rows,
/// i.e. the horizontal part of the estimated up direction seen from the
/// reference attitude: zero when both agree on gravity, |r| sigma = the tilt
/// angle between them (to first order, and sin of it exactly), independent of yaw.
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace storey::backend {

class TiltPriorCost : public ceres::SizedCostFunction<2, 4> {
 public:
  /// q_world_ref: the attitude whose gravity direction the keyframe is held to.
  TiltPriorCost(const Eigen::Quaterniond& q_world_ref, double sigma) {
    A_ = q_world_ref.normalized().toRotationMatrix().topRows<2>() / sigma;
  }

  /// Parameters: q_world_kf (x, y, z, w). g = the third row of R(q):
  /// (2(xz - wy), 2(yz + wx), 1 - 2(x^2 + y^2)).
  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const double x = parameters[0][0], y = parameters[0][1], z = parameters[0][2],
                 w = parameters[0][3];
    const Eigen::Vector3d g(2.0 * (x * z - w * y), 2.0 * (y * z + w * x),
                            1.0 - 2.0 * (x * x + y * y));
    Eigen::Map<Eigen::Vector2d> r(residual);
    r = A_ * g;
    if (jacobians && jacobians[0]) {
      Eigen::Matrix<double, 3, 4> dg_dq;
      dg_dq << 2.0 * z, -2.0 * w, 2.0 * x, -2.0 * y,  //
          2.0 * w, 2.0 * z, 2.0 * y, 2.0 * x,         //
          -4.0 * x, -4.0 * y, 0.0, 0.0;
      Eigen::Map<Eigen::Matrix<double, 2, 4, Eigen::RowMajor>> J(jacobians[0]);
      J = A_ * dg_dq;
    }
    return true;
  }

 private:
  Eigen::Matrix<double, 2, 3> A_;
};

}  // namespace storey::backend
