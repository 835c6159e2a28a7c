#pragma once
/// LiDAR residuals of the odometry, on the IMU pose block of
/// imu/imu_state_blocks.h ([p_world_imu (3), q_world_imu x y z w (4)]).
///
/// A feature point x_lidar is first moved into the IMU frame with the fixed
/// extrinsic: y = T_imu_lidar * x_lidar; in the world it is
///   x_world = R(q) y + p.
///
/// Point-to-plane (planar features; plane n . x = d fitted to map points):
///   r = w (n . x_world - d)                                    (1 residual)
/// Point-to-line (edge features; line through a with unit direction u):
///   r = w (x_world - a) x u                                    (3 residuals)
/// |r| / w is the point's distance to the plane or line. The weight w is
/// 1 / sigma with sigma the combined uncertainty of the point and of the fit
/// [m], so the residuals are whitened (covariance-weighted) like the IMU factor's.
///
/// Jacobians (analytic, with respect to the 7 ambient coordinates; Ceres
/// applies the pose manifold's PlusJacobian): dx_world/dp = I and, for a unit
/// quaternion q = (v, w_q), R(q) y = y + 2 w_q (v x y) + 2 v x (v x y), so
///   dx_world/dv   = -2 w_q [y]x + 2 (v y^T + (v . y) I - 2 y v^T)
///   dx_world/dw_q = 2 v x y
/// Point-to-plane: dr/dx_world = w n^T; point-to-line: dr/dx_world = -w [u]x.
#include <ceres/sized_cost_function.h>
#include <Eigen/Core>

namespace storey {

/// d x_world / d [p, q] (3 x 7, ambient) and x_world for y in the IMU frame.
void worldPointJacobian(const double* pose, const Eigen::Vector3d& y_imu, Eigen::Vector3d& x_world,
                        Eigen::Matrix<double, 3, 7>* jacobian);

class PointToPlaneFactor : public ceres::SizedCostFunction<1, 7> {
 public:
  /// y_imu: the feature point in the IMU frame; plane n . x = d in the world; weight 1/sigma [1/m].
  PointToPlaneFactor(const Eigen::Vector3d& y_imu, const Eigen::Vector3d& n_world, double d_world,
                     double weight);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d y_imu_;
  Eigen::Vector3d n_world_;
  double d_world_;
  double weight_;
};

class PointToLineFactor : public ceres::SizedCostFunction<3, 7> {
 public:
  /// y_imu: the feature point in the IMU frame; line through a_world along unit u_world.
  PointToLineFactor(const Eigen::Vector3d& y_imu, const Eigen::Vector3d& a_world,
                    const Eigen::Vector3d& u_world, double weight);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d y_imu_;
  Eigen::Vector3d a_world_;
  Eigen::Vector3d u_world_;
  double weight_;
};

}  // namespace storey

#include <vector>

#include "odometry/scan_matcher.h"

namespace storey {

/// All LiDAR residuals of one scan in one Ceres cost function (one residual
/// block instead of thousands: Ceres' per-block overhead dominated the solve).
/// Residuals are the point-to-plane and point-to-line ones above, each
/// weighted by 1 / sigma of its match and by the square root of its Huber
/// weight on the whitened distance, min(1, huber_threshold / (|distance| / sigma)),
/// computed from the distance at the pose given to the constructor
/// (iteratively reweighted least squares; the odometry re-associates and
/// reweighs at every matching round). The threshold is in standard
/// deviations (1.345: 95 % efficiency on Gaussian residuals), so a match
/// with an uncertain fit (large sigma) is down-weighted later than a sharp one.
class ScanResidualsFactor final : public ceres::CostFunction {
 public:
  ScanResidualsFactor(const MatchResult& matches, const double* pose_for_weights,
                      double huber_threshold);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  int planeCount() const { return static_cast<int>(planes_.size()); }
  int lineCount() const { return static_cast<int>(lines_.size()); }
  /// At `pose`: the sum of the squared residuals and, with H and g, the
  /// normal equations of the residuals in the ambient coordinates,
  /// H = sum J_i^T J_i and g = sum J_i^T r_i, up to a change along the
  /// quaternion itself (which the pose manifold never makes).
  void normalEquations(const double* pose, double& cost, Eigen::Matrix<double, 7, 7>* H,
                       Eigen::Matrix<double, 7, 1>* g) const;

 private:
  struct Plane {
    Eigen::Vector3d y_imu, n_world;
    double d_world, weight;
  };
  struct Line {
    Eigen::Vector3d y_imu, a_world, u_world;
    double weight;
  };
  std::vector<Plane> planes_;
  std::vector<Line> lines_;
};

/// The same least-squares problem as a ScanResidualsFactor in 8 residuals:
/// with H = V diag(lambda) V^T and g its normal equations at the evaluated
/// pose and c its cost (sum of squared residuals),
///   r' = [diag(lambda)^-1/2 V^T g ; sqrt(c - |that|^2)],  J' = [diag(lambda)^1/2 V^T ; 0],
/// so J'^T J' = H, J'^T r' = g and |r'|^2 = c: Gauss-Newton and
/// Levenberg-Marquardt take the same steps and see the same cost, while Ceres
/// handles 8 rows instead of one per point (its per-row work, validation,
/// scaling and products, was most of the odometry's solve).
class CompressedScanFactor final : public ceres::SizedCostFunction<8, 7> {
 public:
  /// As ScanResidualsFactor's constructor.
  CompressedScanFactor(const MatchResult& matches, const double* pose_for_weights,
                       double huber_threshold);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  ScanResidualsFactor residuals_;
};

}  // namespace storey
