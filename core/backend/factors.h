#pragma once
/// Residuals of the keyframe graph (docs/method/backend.md has the maths).
///
/// Parameter blocks: a keyframe pose is q_world_kf (4, Eigen order x y z w,
/// on ceres::EigenQuaternionManifold) and t_world_kf (3); a plane landmark is
/// n_world (3, unit, on ceres::SphereManifold<3>) and d_world (1). A landmark
/// is oriented: the keyframes that observe it are on the side opposite
/// n_world (n . x < d for their origin), so d_world may be negative.
#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "backend/plane_math.h"
#include "types/pose.h"

namespace storey::backend {

/// Plane observation: the landmark predicted in the keyframe frame,
///   n_kf = R^T n_world,  d_kf = d_world - n_world . t,
/// against the observed (n_obs, d_obs) in the tangent basis B of n_obs:
///   r = L^T [ B^T n_kf ; d_kf - d_obs ],
/// with L L^T the information of the fit in the same coordinates (a1, a2, d).
struct PlaneObservationFactor {
  PlaneObservationFactor(const Eigen::Vector3d& n_obs, double d_obs,
                         const Eigen::Matrix3d& sqrt_information)
      : B_t(tangentBasis(n_obs).transpose()), d_obs(d_obs), sqrt_information(sqrt_information) {}

  template <typename T>
  bool operator()(const T* q_world_kf, const T* t_world_kf, const T* n_world, const T* d_world,
                  T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q(q_world_kf);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t(t_world_kf);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> n(n_world);
    const Eigen::Matrix<T, 3, 1> n_kf = q.conjugate() * n;
    Eigen::Matrix<T, 3, 1> e;
    e.template head<2>() = B_t.cast<T>() * n_kf;
    e(2) = d_world[0] - n.dot(t) - T(d_obs);
    Eigen::Map<Eigen::Matrix<T, 3, 1>> r(residual);
    r = sqrt_information.cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& n_obs, double d_obs,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<PlaneObservationFactor, 3, 4, 3, 3, 1>(
        new PlaneObservationFactor(n_obs, d_obs, sqrt_information));
  }

  Eigen::Matrix<double, 2, 3> B_t;
  double d_obs;
  Eigen::Matrix3d sqrt_information;
};

/// Relative pose from the odometry between keyframes a and b (T_a_b measured):
///   r = L^T [ R_a^T (t_b - t_a) - t_ab ; 2 vec(q_ab^-1 q_a^-1 q_b) ],
/// translation first, in the frame of a; L L^T the 6x6 information.
struct RelativePoseFactor {
  RelativePoseFactor(const Pose& T_a_b, const Eigen::Matrix<double, 6, 6>& sqrt_information)
      : q_ab(T_a_b.rotation()), t_ab(T_a_b.translation()), sqrt_information(sqrt_information) {}

  template <typename T>
  bool operator()(const T* qa, const T* ta, const T* qb, const T* tb, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(qa), q_b(qb);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t_a(ta), t_b(tb);
    const Eigen::Quaternion<T> q_a_inv = q_a.conjugate();
    const Eigen::Matrix<T, 3, 1> t_ab_est = q_a_inv * (t_b - t_a);
    const Eigen::Quaternion<T> dq = q_ab.conjugate().cast<T>() * (q_a_inv * q_b);
    Eigen::Matrix<T, 6, 1> e;
    e.template head<3>() = t_ab_est - t_ab.cast<T>();
    e.template tail<3>() = T(2.0) * dq.vec();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r = sqrt_information.cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* create(const Pose& T_a_b,
                                     const Eigen::Matrix<double, 6, 6>& sqrt_information) {
    return new ceres::AutoDiffCostFunction<RelativePoseFactor, 6, 4, 3, 4, 3>(
        new RelativePoseFactor(T_a_b, sqrt_information));
  }

  Eigen::Quaterniond q_ab;
  Eigen::Vector3d t_ab;
  Eigen::Matrix<double, 6, 6> sqrt_information;
};

/// RelativePoseFactor with the translation in the heading frame of a
/// (graph.heading_frame_edges; docs/method/backend.md, "Relative-pose
/// factor"): the odometry's displacement, levelled, compared with the
/// graph's after turning it by a's yaw correction only,
///   C = q_a conj(q_world_odom q_odom_a),  psi = 2 atan2(C_z, C_w),
///   e = [ Rz(psi)^T (t_b - t_a) - q_world_odom q_odom_a t_ab ;  2 vec(q_ab^-1 q_a^-1 q_b) ],
///   r = L^T e.
/// A tilt of keyframe a (the graph levelling it differently from the
/// odometry) leaves the translation residual unchanged: the odometry's
/// height differences stay height differences. `q_world_odom` points to the
/// graph's current levelling of the odometry's map frame, read at every
/// evaluation; `q_odom_a` is a's attitude in that frame.
struct HeadingRelativePoseFactor {
  HeadingRelativePoseFactor(const Pose& T_a_b, const Eigen::Quaterniond& q_odom_a,
                            const Eigen::Quaterniond* q_world_odom,
                            const Eigen::Matrix<double, 6, 6>& sqrt_information)
      : q_ab(T_a_b.rotation()),
        t_ab(T_a_b.translation()),
        q_odom_a(q_odom_a),
        q_world_odom(q_world_odom),
        sqrt_information(sqrt_information) {}

  /// The odometry's displacement from a to b in the levelled world frame.
  Eigen::Vector3d levelledDisplacement() const { return *q_world_odom * (q_odom_a * t_ab); }
  /// conj(q_world_odom q_odom_a): C = q_a * this.
  Eigen::Quaterniond referenceInverse() const { return (*q_world_odom * q_odom_a).conjugate(); }

  template <typename T>
  bool operator()(const T* qa, const T* ta, const T* qb, const T* tb, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(qa), q_b(qb);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t_a(ta), t_b(tb);
    const Eigen::Vector3d delta = levelledDisplacement();
    const Eigen::Quaternion<T> C = q_a * referenceInverse().cast<T>();
    const T n2 = C.z() * C.z() + C.w() * C.w();
    const T c = (C.w() * C.w() - C.z() * C.z()) / n2;  // cos psi
    const T s = T(2.0) * C.w() * C.z() / n2;           // sin psi
    const Eigen::Matrix<T, 3, 1> v = t_b - t_a;
    Eigen::Matrix<T, 6, 1> e;
    e(0) = c * v(0) + s * v(1) - T(delta(0));
    e(1) = -s * v(0) + c * v(1) - T(delta(1));
    e(2) = v(2) - T(delta(2));
    const Eigen::Quaternion<T> dq = q_ab.conjugate().cast<T>() * (q_a.conjugate() * q_b);
    e.template tail<3>() = T(2.0) * dq.vec();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r = sqrt_information.cast<T>() * e;
    return true;
  }

  Eigen::Quaterniond q_ab;
  Eigen::Vector3d t_ab;
  Eigen::Quaterniond q_odom_a;
  const Eigen::Quaterniond* q_world_odom;
  Eigen::Matrix<double, 6, 6> sqrt_information;
};

/// Prior on a rotation q (4, Eigen order) about its initial value q0:
///   r = L^T 2 vec(q0^-1 q),
/// with L L^T the information of the body-frame rotation error. The first
/// keyframe gets it: yaw (about world z) held, roll and pitch as uncertain as
/// the IMU initialisation (the level floors decide them).
struct RotationPriorFactor {
  RotationPriorFactor(const Eigen::Quaterniond& q0, const Eigen::Matrix3d& sqrt_information)
      : q0(q0), sqrt_information(sqrt_information) {}

  template <typename T>
  bool operator()(const T* q, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> qq(q);
    const Eigen::Quaternion<T> dq = q0.conjugate().cast<T>() * qq;
    Eigen::Map<Eigen::Matrix<T, 3, 1>> r(residual);
    r = sqrt_information.cast<T>() * (T(2.0) * dq.vec());
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Quaterniond& q0,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<RotationPriorFactor, 3, 4>(
        new RotationPriorFactor(q0, sqrt_information));
  }

  Eigen::Quaterniond q0;
  Eigen::Matrix3d sqrt_information;
};

/// Floors and ceilings are level, walls plumb (the world is gravity-aligned):
/// level:  r = (n_x, n_y) / sigma  (normal along +-z);
/// plumb:  r = n_z / sigma         (normal horizontal).
struct LevelPriorFactor {
  LevelPriorFactor(bool level, double sigma) : level(level), inv_sigma(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* n_world, T* residual) const {
    if (level) {
      residual[0] = T(inv_sigma) * n_world[0];
      residual[1] = T(inv_sigma) * n_world[1];
    } else {
      residual[0] = T(inv_sigma) * n_world[2];
      residual[1] = T(0.0);
    }
    return true;
  }

  static ceres::CostFunction* create(bool level, double sigma) {
    return new ceres::AutoDiffCostFunction<LevelPriorFactor, 2, 3>(
        new LevelPriorFactor(level, sigma));
  }

  bool level;
  double inv_sigma;
};

}  // namespace storey::backend
