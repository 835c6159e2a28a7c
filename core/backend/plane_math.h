#pragma once
/// Small helpers shared by SRP extraction, association and the plane factor:
/// the tangent basis of a unit normal, in which plane uncertainties and plane
/// residuals are expressed (docs/method/backend.md, "Plane parametrisation").
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace storey::backend {

/// Two unit vectors orthogonal to the unit vector n and to each other
/// (columns), a deterministic function of n: b1 = normalise(n x a) with a the
/// coordinate axis least aligned with n, b2 = n x b1.
inline Eigen::Matrix<double, 3, 2> tangentBasis(const Eigen::Vector3d& n) {
  Eigen::Vector3d a = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d m = n.cwiseAbs();
  if (m.y() <= m.x() && m.y() <= m.z()) a = Eigen::Vector3d::UnitY();
  else if (m.z() <= m.x() && m.z() <= m.y()) a = Eigen::Vector3d::UnitZ();
  Eigen::Matrix<double, 3, 2> B;
  B.col(0) = n.cross(a).normalized();
  B.col(1) = n.cross(B.col(0));
  return B;
}

inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

/// Upper-triangular square root L^T of an information matrix (L L^T = info),
/// so that r^T info r = |L^T r|^2; a matrix that is not positive definite is
/// regularised on its diagonal first.
template <int N>
Eigen::Matrix<double, N, N> sqrtInformation(Eigen::Matrix<double, N, N> information) {
  Eigen::LLT<Eigen::Matrix<double, N, N>> llt(information);
  if (llt.info() != Eigen::Success) {
    information.diagonal().array() += 1e-9 * information.diagonal().cwiseAbs().maxCoeff() + 1e-12;
    llt.compute(information);
  }
  return llt.matrixU();
}

}  // namespace storey::backend
