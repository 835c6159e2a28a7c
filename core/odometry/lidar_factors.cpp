#include "odometry/lidar_factors.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "imu/so3.h"

namespace storey {
using so3::skew;

void worldPointJacobian(const double* pose, const Eigen::Vector3d& y_imu, Eigen::Vector3d& x_world,
                        Eigen::Matrix<double, 3, 7>* jacobian) {
  const Eigen::Map<const Eigen::Vector3d> p(pose);
  const Eigen::Map<const Eigen::Quaterniond> q(pose + 3);
  const Eigen::Vector3d v = q.vec();
  const double w = q.w();
  const Eigen::Vector3d v_cross_y = v.cross(y_imu);
  x_world = y_imu + 2.0 * w * v_cross_y + 2.0 * v.cross(v_cross_y) + p;
  if (jacobian) {
    jacobian->leftCols<3>().setIdentity();
    jacobian->block<3, 3>(0, 3) =
        -2.0 * w * skew(y_imu) +
        2.0 * (v * y_imu.transpose() + v.dot(y_imu) * Eigen::Matrix3d::Identity() -
               2.0 * y_imu * v.transpose());
    jacobian->col(6) = 2.0 * v_cross_y;
  }
}

PointToPlaneFactor::PointToPlaneFactor(const Eigen::Vector3d& y_imu, const Eigen::Vector3d& n_world,
                                       double d_world, double weight)
    : y_imu_(y_imu), n_world_(n_world), d_world_(d_world), weight_(weight) {}

bool PointToPlaneFactor::Evaluate(double const* const* parameters, double* residuals,
                                  double** jacobians) const {
  Eigen::Vector3d x_world;
  Eigen::Matrix<double, 3, 7> J;
  const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  worldPointJacobian(parameters[0], y_imu_, x_world, want_jacobian ? &J : nullptr);
  residuals[0] = weight_ * (n_world_.dot(x_world) - d_world_);
  if (want_jacobian) {
    Eigen::Map<Eigen::Matrix<double, 1, 7>> out(jacobians[0]);
    out = weight_ * n_world_.transpose() * J;
  }
  return true;
}

PointToLineFactor::PointToLineFactor(const Eigen::Vector3d& y_imu, const Eigen::Vector3d& a_world,
                                     const Eigen::Vector3d& u_world, double weight)
    : y_imu_(y_imu), a_world_(a_world), u_world_(u_world.normalized()), weight_(weight) {}

bool PointToLineFactor::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  Eigen::Vector3d x_world;
  Eigen::Matrix<double, 3, 7> J;
  const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  worldPointJacobian(parameters[0], y_imu_, x_world, want_jacobian ? &J : nullptr);
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = weight_ * (x_world - a_world_).cross(u_world_);
  if (want_jacobian) {
    Eigen::Map<Eigen::Matrix<double, 3, 7, Eigen::RowMajor>> out(jacobians[0]);
    out = -weight_ * skew(u_world_) * J;
  }
  return true;
}

}  // namespace storey

namespace storey {

ScanResidualsFactor::ScanResidualsFactor(const MatchResult& matches, const double* pose_for_weights,
                                         double huber_threshold) {
  planes_.reserve(matches.planes.size());
  lines_.reserve(matches.lines.size());
  const auto huberWeight = [huber_threshold](double whitened) {
    const double a = std::abs(whitened);
    return a <= huber_threshold ? 1.0 : huber_threshold / a;
  };
  Eigen::Vector3d x_world;
  for (const PlaneMatch& m : matches.planes) {
    worldPointJacobian(pose_for_weights, m.y_imu, x_world, nullptr);
    const double distance = m.n_world.dot(x_world) - m.d_world;
    planes_.push_back(
        {m.y_imu, m.n_world, m.d_world, std::sqrt(huberWeight(distance / m.sigma)) / m.sigma});
  }
  for (const LineMatch& m : matches.lines) {
    worldPointJacobian(pose_for_weights, m.y_imu, x_world, nullptr);
    const Eigen::Vector3d u = m.u_world.normalized();
    const double distance = (x_world - m.a_world).cross(u).norm();
    lines_.push_back({m.y_imu, m.a_world, u, std::sqrt(huberWeight(distance / m.sigma)) / m.sigma});
  }
  set_num_residuals(static_cast<int>(planes_.size() + 3 * lines_.size()));
  mutable_parameter_block_sizes()->push_back(7);
}

bool ScanResidualsFactor::Evaluate(double const* const* parameters, double* residuals,
                                   double** jacobians) const {
  const double* pose = parameters[0];
  const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  Eigen::Vector3d x_world;
  Eigen::Matrix<double, 3, 7> J;
  std::size_t row = 0;
  for (const Plane& p : planes_) {
    worldPointJacobian(pose, p.y_imu, x_world, want_jacobian ? &J : nullptr);
    residuals[row] = p.weight * (p.n_world.dot(x_world) - p.d_world);
    if (want_jacobian) {
      Eigen::Map<Eigen::Matrix<double, 1, 7>> out(jacobians[0] + 7 * row);
      out = p.weight * p.n_world.transpose() * J;
    }
    ++row;
  }
  for (const Line& l : lines_) {
    worldPointJacobian(pose, l.y_imu, x_world, want_jacobian ? &J : nullptr);
    Eigen::Map<Eigen::Vector3d> r(residuals + row);
    r = l.weight * (x_world - l.a_world).cross(l.u_world);
    if (want_jacobian) {
      Eigen::Map<Eigen::Matrix<double, 3, 7, Eigen::RowMajor>> out(jacobians[0] + 7 * row);
      out = -l.weight * skew(l.u_world) * J;
    }
    row += 3;
  }
  return true;
}

namespace {

/// H += row row^T on the upper triangle.
template <int N>
inline void addOuterUpper(const double* row, Eigen::Matrix<double, N, N>& H) {
  for (int j = 0; j < N; ++j)
    for (int i = 0; i <= j; ++i) H(i, j) += row[i] * row[j];
}

}  // namespace

void ScanResidualsFactor::normalEquations(const double* pose, double& cost,
                                          Eigen::Matrix<double, 7, 7>* H,
                                          Eigen::Matrix<double, 7, 1>* g) const {
  cost = 0.0;
  const bool want_jacobian = H != nullptr && g != nullptr;
  const Eigen::Map<const Eigen::Vector3d> p_world(pose);
  const Eigen::Map<const Eigen::Quaterniond> q(pose + 3);
  const Eigen::Matrix3d R = q.toRotationMatrix();
  // Planes: in the tangent [dp, theta] with R -> Exp(theta) R, d(R y)/dtheta
  // = -[R y]x, so a point's row is w [n, (R y) x n]; summed there (6 x 6),
  // then taken to the ambient coordinates below.
  Eigen::Matrix<double, 6, 6> H_tangent = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> g_tangent = Eigen::Matrix<double, 6, 1>::Zero();
  for (const Plane& plane : planes_) {
    const Eigen::Vector3d& n = plane.n_world;
    const Eigen::Vector3d Ry = R * plane.y_imu;
    const double r = plane.weight * (n.dot(Ry + p_world) - plane.d_world);
    cost += r * r;
    if (!want_jacobian) continue;
    const Eigen::Vector3d d_theta = plane.weight * Ry.cross(n);
    const double row[6] = {plane.weight * n.x(), plane.weight * n.y(), plane.weight * n.z(),
                           d_theta.x(),          d_theta.y(),          d_theta.z()};
    addOuterUpper<6>(row, H_tangent);
    for (int i = 0; i < 6; ++i) g_tangent(i) += r * row[i];
  }
  if (!want_jacobian) {
    for (const Line& l : lines_) {
      const Eigen::Vector3d x_world = R * l.y_imu + p_world;
      cost += (l.weight * (x_world - l.a_world).cross(l.u_world)).squaredNorm();
    }
    return;
  }
  // theta of a change dq of the ambient quaternion (x, y, z, w) at unit q:
  // 2 vec(dq q*) = M dq with M = 2 [w I + [v]x, -v] (zero along q itself).
  const Eigen::Vector3d v = q.vec();
  Eigen::Matrix<double, 6, 7> A = Eigen::Matrix<double, 6, 7>::Zero();
  A.topLeftCorner<3, 3>().setIdentity();
  A.block<3, 3>(3, 3) = 2.0 * (q.w() * Eigen::Matrix3d::Identity() + skew(v));
  A.block<3, 1>(3, 6) = -2.0 * v;
  H_tangent.triangularView<Eigen::StrictlyLower>() = H_tangent.transpose();
  *H = A.transpose() * H_tangent * A;
  *g = A.transpose() * g_tangent;
  Eigen::Vector3d x_world;
  Eigen::Matrix<double, 3, 7> J;
  for (const Line& l : lines_) {
    worldPointJacobian(pose, l.y_imu, x_world, &J);
    const Eigen::Vector3d r = l.weight * (x_world - l.a_world).cross(l.u_world);
    cost += r.squaredNorm();
    const Eigen::Matrix<double, 3, 7> rows = -l.weight * skew(l.u_world) * J;
    *H += rows.transpose() * rows;
    *g += rows.transpose() * r;
  }
}

CompressedScanFactor::CompressedScanFactor(const MatchResult& matches,
                                           const double* pose_for_weights, double huber_threshold)
    : residuals_(matches, pose_for_weights, huber_threshold) {}

bool CompressedScanFactor::Evaluate(double const* const* parameters, double* residuals,
                                    double** jacobians) const {
  const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  double cost = 0.0;
  Eigen::Map<Eigen::Matrix<double, 8, 1>> r(residuals);
  r.setZero();
  if (!want_jacobian) {
    residuals_.normalEquations(parameters[0], cost, nullptr, nullptr);
    r(7) = std::sqrt(cost);
    return std::isfinite(cost);
  }
  Eigen::Matrix<double, 7, 7> H;
  Eigen::Matrix<double, 7, 1> g;
  residuals_.normalEquations(parameters[0], cost, &H, &g);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 7, 7>> eigen(H);
  const Eigen::Matrix<double, 7, 1>& lambda = eigen.eigenvalues();
  const Eigen::Matrix<double, 7, 7>& V = eigen.eigenvectors();
  Eigen::Map<Eigen::Matrix<double, 8, 7, Eigen::RowMajor>> J(jacobians[0]);
  J.setZero();
  // Directions without information (eigenvalues at rounding level of the
  // largest) get neither a row nor a residual: g has no part there.
  const double floor = 1e-12 * std::max(lambda.maxCoeff(), 0.0);
  double explained = 0.0;
  for (int k = 0; k < 7; ++k) {
    if (!(lambda(k) > floor)) continue;
    const double root = std::sqrt(lambda(k));
    J.row(k) = root * V.col(k).transpose();
    r(k) = V.col(k).dot(g) / root;
    explained += r(k) * r(k);
  }
  r(7) = std::sqrt(std::max(cost - explained, 0.0));
  return std::isfinite(cost) && J.allFinite();
}

}  // namespace storey
