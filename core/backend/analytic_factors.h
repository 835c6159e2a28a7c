#pragma once
/// Analytic Jacobians of the factors the windowed solve evaluates most
/// (plane observations, by free and by held keyframes, and odometry edges):
/// the residuals of factors.h's PlaneObservationFactor and
/// RelativePoseFactor, whose templated functors stay the reference
/// (tests/unit/backend/factors_test.cpp checks these against them and against numeric
/// differentiation). Automatic differentiation carried 11 and 14 derivative parts through every
/// operation; these are a few small matrix products (docs/method/backend.md).
///
/// Both differentiate the same polynomial Eigen evaluates for a quaternion
/// (x, y, z, w) = (u, w) rotating a vector by its conjugate,
///   f(q, v) = v + 2w (u' x v) + 2 u' x (u' x v),  u' = -u,
/// with respect to all four components (Ceres' EigenQuaternionManifold maps
/// them to the tangent space).
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "backend/factors.h"
#include "backend/plane_math.h"

namespace storey::backend {

/// f(q, v) = conj(q) v: its Jacobian in q (3x4, columns x y z w) and the
/// linear map M(q) with f = M v (= R(q)^T for a unit q).
inline void conjugateRotationJacobians(const Eigen::Quaterniond& q, const Eigen::Vector3d& v,
                                       Eigen::Matrix<double, 3, 4>& df_dq, Eigen::Matrix3d& M) {
  const Eigen::Vector3d u = -q.vec();
  const double w = q.w();
  const Eigen::Vector3d c = u.cross(v);
  const Eigen::Matrix3d U = skew(u);
  // d f / d u' = -2w [v]x - 2 [u']x [v]x - 2 [c]x, and u' = -u.
  df_dq.leftCols<3>() = 2.0 * (w * skew(v) + U * skew(v) + skew(c));
  df_dq.col(3) = 2.0 * c;
  M = Eigen::Matrix3d::Identity() + 2.0 * w * U + 2.0 * U * U;
}

/// a * b = QL(a) b = QR(b) a, quaternions as 4-vectors (x, y, z, w).
inline Eigen::Matrix4d quaternionLeft(const Eigen::Quaterniond& a) {
  Eigen::Matrix4d m;
  m.topLeftCorner<3, 3>() = a.w() * Eigen::Matrix3d::Identity() + skew(a.vec());
  m.topRightCorner<3, 1>() = a.vec();
  m.bottomLeftCorner<1, 3>() = -a.vec().transpose();
  m(3, 3) = a.w();
  return m;
}
inline Eigen::Matrix4d quaternionRight(const Eigen::Quaterniond& b) {
  Eigen::Matrix4d m;
  m.topLeftCorner<3, 3>() = b.w() * Eigen::Matrix3d::Identity() - skew(b.vec());
  m.topRightCorner<3, 1>() = b.vec();
  m.bottomLeftCorner<1, 3>() = -b.vec().transpose();
  m(3, 3) = b.w();
  return m;
}

/// PlaneObservationFactor with analytic Jacobians. Parameters: q_world_kf (4),
/// t_world_kf (3), n_world (3), d_world (1). With f = conj(q) n, e = [B^T f ;
/// d - n.t - d_obs] and r = L^T e:
///   dr/dq = L^T[:, 0:2] B^T df/dq,  dr/dt = -L^T[:, 2] n^T,
///   dr/dn = L^T[:, 0:2] B^T M - L^T[:, 2] t^T,  dr/dd = L^T[:, 2].
class PlaneObservationCost : public ceres::SizedCostFunction<3, 4, 3, 3, 1> {
 public:
  explicit PlaneObservationCost(const PlaneObservationFactor& factor) : f_(factor) {}

  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Quaterniond> q(parameters[0]);
    const Eigen::Map<const Eigen::Vector3d> t(parameters[1]);
    const Eigen::Map<const Eigen::Vector3d> n(parameters[2]);
    const double d = parameters[3][0];
    const Eigen::Vector3d n_kf = q.conjugate() * n;
    Eigen::Vector3d e;
    e.head<2>() = f_.B_t * n_kf;
    e(2) = d - n.dot(t) - f_.d_obs;
    Eigen::Map<Eigen::Vector3d> r(residual);
    r = f_.sqrt_information * e;
    if (!jacobians) return true;
    const Eigen::Matrix<double, 3, 2> S_normal = f_.sqrt_information.leftCols<2>();
    const Eigen::Vector3d S_distance = f_.sqrt_information.col(2);
    Eigen::Matrix<double, 3, 4> dnkf_dq;
    Eigen::Matrix3d M;
    conjugateRotationJacobians(q, n, dnkf_dq, M);
    if (jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> J(jacobians[0]);
      J = S_normal * (f_.B_t * dnkf_dq);
    }
    if (jacobians[1]) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(jacobians[1]);
      J = -S_distance * n.transpose();
    }
    if (jacobians[2]) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(jacobians[2]);
      J = S_normal * (f_.B_t * M) - S_distance * t.transpose();
    }
    if (jacobians[3]) {
      Eigen::Map<Eigen::Vector3d> J(jacobians[3]);
      J = S_distance;
    }
    return true;
  }

 private:
  PlaneObservationFactor f_;
};

/// The same plane observation by a keyframe held fixed in a windowed solve:
/// its pose (R, t) is a constant, so the residual is linear in the plane,
///   r = L^T [ B^T R^T n ; d - t . n - d_obs ] = J_n n + J_d d - L^T (0, 0, d_obs),
/// with the constant Jacobians J_n = L^T [B^T R^T ; -t^T] (3x3) and
/// J_d = L^T (0, 0, 1) computed once (analytic: no automatic differentiation).
class HeldPlaneObservationFactor : public ceres::SizedCostFunction<3, 3, 1> {
 public:
  HeldPlaneObservationFactor(const PlaneObservationFactor& observation,
                             const Eigen::Matrix3d& R_world_kf, const Eigen::Vector3d& t_world_kf) {
    const Eigen::Matrix3d& L_t = observation.sqrt_information;
    Eigen::Matrix3d A;
    A.topRows<2>() = observation.B_t * R_world_kf.transpose();
    A.row(2) = -t_world_kf.transpose();
    J_n_ = L_t * A;
    J_d_ = L_t.col(2);
    offset_ = L_t.col(2) * observation.d_obs;
  }

  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Vector3d> n(parameters[0]);
    const double d = parameters[1][0];
    Eigen::Map<Eigen::Vector3d> r(residual);
    r = J_n_ * n + J_d_ * d - offset_;
    if (jacobians && jacobians[0]) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> dr_dn(jacobians[0]);
      dr_dn = J_n_;
    }
    if (jacobians && jacobians[1]) {
      Eigen::Map<Eigen::Vector3d> dr_dd(jacobians[1]);
      dr_dd = J_d_;
    }
    return true;
  }

 private:
  Eigen::Matrix3d J_n_;
  Eigen::Vector3d J_d_, offset_;
};

/// The residual r = L^T [e_t ; 2 vec(conj(q_ab) conj(q_a) q_b)] of both
/// relative-pose costs, given their translation rows e_t.
inline void relativePoseResidual(const Eigen::Matrix<double, 6, 6>& sqrt_information,
                                 const Eigen::Quaterniond& q_ab, const Eigen::Quaterniond& q_a,
                                 const Eigen::Quaterniond& q_b, const Eigen::Vector3d& e_t,
                                 double* residual) {
  const Eigen::Quaterniond dq = q_ab.conjugate() * (q_a.conjugate() * q_b);
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() = e_t;
  e.tail<3>() = 2.0 * dq.vec();
  Eigen::Map<Eigen::Matrix<double, 6, 1>> r(residual);
  r = sqrt_information * e;
}

/// Their Jacobians in (q_a, t_a, q_b, t_b) (null blocks: not wanted), given
/// the translation rows' Jacobian in q_a and in t_b (that in t_a is its
/// negative). The rotation rows: with C = diag(-1, -1, -1, 1),
///   de_r/dq_a = 2 (QL(conj q_ab) QR(q_b) C)_vec,  de_r/dq_b = 2 (QL(conj q_ab) QL(conj q_a))_vec.
inline void relativePoseJacobians(const Eigen::Matrix<double, 6, 6>& sqrt_information,
                                  const Eigen::Quaterniond& q_ab, const Eigen::Quaterniond& q_a,
                                  const Eigen::Quaterniond& q_b,
                                  const Eigen::Matrix<double, 3, 4>& de_t_dqa,
                                  const Eigen::Matrix3d& de_t_dtb, double** jacobians) {
  const Eigen::Matrix<double, 6, 3> S_translation = sqrt_information.leftCols<3>();
  const Eigen::Matrix<double, 6, 3> S_rotation = sqrt_information.rightCols<3>();
  const Eigen::Matrix4d L_ab = quaternionLeft(q_ab.conjugate());
  if (jacobians[0]) {
    Eigen::Matrix4d ddq_dqa = L_ab * quaternionRight(q_b);
    ddq_dqa.leftCols<3>() *= -1.0;  // d conj(q_a) / d q_a
    Eigen::Map<Eigen::Matrix<double, 6, 4, Eigen::RowMajor>> J(jacobians[0]);
    J = S_translation * de_t_dqa + S_rotation * (2.0 * ddq_dqa.topRows<3>());
  }
  if (jacobians[1]) {
    Eigen::Map<Eigen::Matrix<double, 6, 3, Eigen::RowMajor>> J(jacobians[1]);
    J = -S_translation * de_t_dtb;
  }
  if (jacobians[2]) {
    const Eigen::Matrix4d ddq_dqb = L_ab * quaternionLeft(q_a.conjugate());
    Eigen::Map<Eigen::Matrix<double, 6, 4, Eigen::RowMajor>> J(jacobians[2]);
    J = S_rotation * (2.0 * ddq_dqb.topRows<3>());
  }
  if (jacobians[3]) {
    Eigen::Map<Eigen::Matrix<double, 6, 3, Eigen::RowMajor>> J(jacobians[3]);
    J = S_translation * de_t_dtb;
  }
}

/// RelativePoseFactor with analytic Jacobians. Parameters: q_a (4), t_a (3),
/// q_b (4), t_b (3). With f = conj(q_a) (t_b - t_a), dq = conj(q_ab) conj(q_a)
/// q_b, e = [f - t_ab ; 2 vec(dq)] and r = L^T e:
///   de/dq_a = [df/dq_a ; 2 (QL(conj q_ab) QR(q_b) C)_vec],  C = diag(-1, -1, -1, 1),
///   de/dt_a = [-M ; 0],  de/dq_b = [0 ; 2 (QL(conj q_ab) QL(conj q_a))_vec],
///   de/dt_b = [M ; 0].
class RelativePoseCost : public ceres::SizedCostFunction<6, 4, 3, 4, 3> {
 public:
  explicit RelativePoseCost(const RelativePoseFactor& factor) : f_(factor) {}

  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Quaterniond> q_a(parameters[0]), q_b(parameters[2]);
    const Eigen::Map<const Eigen::Vector3d> t_a(parameters[1]), t_b(parameters[3]);
    const Eigen::Vector3d v = t_b - t_a;
    relativePoseResidual(f_.sqrt_information, f_.q_ab, q_a, q_b, q_a.conjugate() * v - f_.t_ab,
                         residual);
    if (!jacobians) return true;
    Eigen::Matrix<double, 3, 4> df_dqa;
    Eigen::Matrix3d M;
    conjugateRotationJacobians(q_a, v, df_dqa, M);
    relativePoseJacobians(f_.sqrt_information, f_.q_ab, q_a, q_b, df_dqa, M, jacobians);
    return true;
  }

 private:
  RelativePoseFactor f_;
};

/// HeadingRelativePoseFactor with analytic Jacobians. Parameters as
/// RelativePoseCost. With p = conj(q_world_odom q_odom_a), C = q_a p =
/// QR(p) q_a, psi = 2 atan2(C_z, C_w), u = Rz(psi)^T (t_b - t_a):
///   du/dpsi = (u_y, -u_x, 0),  dpsi/dC = 2 / (C_z^2 + C_w^2) (0, 0, C_w, -C_z),
///   de/dq_a = [du/dpsi dpsi/dC QR(p) ; the rotation rows of RelativePoseCost],
///   de/dt_a = [-Rz(psi)^T ; 0],  de/dt_b = [Rz(psi)^T ; 0],  de/dq_b as RelativePoseCost.
class HeadingRelativePoseCost : public ceres::SizedCostFunction<6, 4, 3, 4, 3> {
 public:
  explicit HeadingRelativePoseCost(const HeadingRelativePoseFactor& factor) : f_(factor) {}

  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Quaterniond> q_a(parameters[0]), q_b(parameters[2]);
    const Eigen::Map<const Eigen::Vector3d> t_a(parameters[1]), t_b(parameters[3]);
    const Eigen::Quaterniond p = f_.referenceInverse();
    const Eigen::Quaterniond C = q_a * p;
    const double n2 = C.z() * C.z() + C.w() * C.w();
    const double c = (C.w() * C.w() - C.z() * C.z()) / n2;
    const double s = 2.0 * C.w() * C.z() / n2;
    const Eigen::Vector3d v = t_b - t_a;
    const Eigen::Vector3d u(c * v.x() + s * v.y(), -s * v.x() + c * v.y(), v.z());
    relativePoseResidual(f_.sqrt_information, f_.q_ab, q_a, q_b, u - f_.levelledDisplacement(),
                         residual);
    if (!jacobians) return true;
    Eigen::Matrix3d Rt;  // Rz(psi)^T
    Rt << c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0;
    const Eigen::RowVector4d dpsi_dC = (2.0 / n2) * Eigen::RowVector4d(0.0, 0.0, C.w(), -C.z());
    const Eigen::Matrix<double, 3, 4> du_dqa =
        Eigen::Vector3d(u.y(), -u.x(), 0.0) * (dpsi_dC * quaternionRight(p));
    relativePoseJacobians(f_.sqrt_information, f_.q_ab, q_a, q_b, du_dqa, Rt, jacobians);
    return true;
  }

 private:
  HeadingRelativePoseFactor f_;
};

/// The odometry's height difference between keyframes a and b
/// (graph.height_span_keyframes, docs/method/backend.md "Height spans"):
///   r = ((t_b - t_a)_z - (q_world_odom d_odom_ab)_z) / sigma,
/// d_odom_ab = p_b - p_a in the odometry's map frame, levelled with the
/// odometry's latest levelling (read at every evaluation, like the heading
/// edges). Jacobians: -1/sigma and 1/sigma on the z of t_a and t_b.
class HeightDifferenceCost : public ceres::SizedCostFunction<1, 3, 3> {
 public:
  HeightDifferenceCost(const Eigen::Vector3d& d_odom_ab, const Eigen::Quaterniond* q_world_odom,
                       double sigma)
      : d_(d_odom_ab), q_world_odom_(q_world_odom), w_(1.0 / sigma) {}

  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    residual[0] = w_ * (parameters[1][2] - parameters[0][2] - ((*q_world_odom_) * d_).z());
    if (!jacobians) return true;
    for (int k = 0; k < 2; ++k) {
      if (!jacobians[k]) continue;
      jacobians[k][0] = jacobians[k][1] = 0.0;
      jacobians[k][2] = k == 0 ? -w_ : w_;
    }
    return true;
  }

 private:
  Eigen::Vector3d d_;
  const Eigen::Quaterniond* q_world_odom_;
  double w_;
};

/// The odometry's height difference between keyframes a and b in keyframe
/// a's frame (graph.height_span_keyframe_frame): the odometry's relative
/// translation p_a_ab = R_odom_a^T (p_odom_b - p_odom_a), turned by the
/// graph's own attitude of a, so a slow tilt of the odometry's map frame
/// (levelled once for the whole log) does not enter the height:
///   r = ((t_b - t_a)_z - (R(q_a) p_a_ab)_z) / sigma.
/// Parameters q_a (x, y, z, w), t_a, t_b. With q = (x, y, z, w) and p:
///   (R p)_z = 2(xz - wy) p_x + 2(yz + wx) p_y + (w^2 - x^2 - y^2 + z^2) p_z.
class KeyframeHeightDifferenceCost : public ceres::SizedCostFunction<1, 4, 3, 3> {
 public:
  KeyframeHeightDifferenceCost(const Eigen::Vector3d& p_a_ab, double sigma)
      : p_(p_a_ab), w_(1.0 / sigma) {}

  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const double x = parameters[0][0], y = parameters[0][1], z = parameters[0][2],
                 w = parameters[0][3];
    const double px = p_.x(), py = p_.y(), pz = p_.z();
    const double rz = 2.0 * (x * z - w * y) * px + 2.0 * (y * z + w * x) * py +
                      (w * w - x * x - y * y + z * z) * pz;
    residual[0] = w_ * (parameters[2][2] - parameters[1][2] - rz);
    if (!jacobians) return true;
    if (jacobians[0]) {
      jacobians[0][0] = -w_ * 2.0 * (z * px + w * py - x * pz);
      jacobians[0][1] = -w_ * 2.0 * (-w * px + z * py - y * pz);
      jacobians[0][2] = -w_ * 2.0 * (x * px + y * py + z * pz);
      jacobians[0][3] = -w_ * 2.0 * (-y * px + x * py + w * pz);
    }
    for (int k = 1; k < 3; ++k) {
      if (!jacobians[k]) continue;
      jacobians[k][0] = jacobians[k][1] = 0.0;
      jacobians[k][2] = k == 1 ? -w_ : w_;
    }
    return true;
  }

 private:
  Eigen::Vector3d p_;
  double w_;
};

}  // namespace storey::backend
