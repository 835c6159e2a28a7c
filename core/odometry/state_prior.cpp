#include "odometry/state_prior.h"

#include <Eigen/Cholesky>
#include <vector>

#include "imu/imu_state_blocks.h"

namespace storey {

StatePriorFactor::StatePriorFactor(const StatePrior& prior)
    : p0_(prior.pose[0], prior.pose[1], prior.pose[2]),
      q0_inverse_(Eigen::Quaterniond(prior.pose[6], prior.pose[3], prior.pose[4], prior.pose[5])
                      .normalized()
                      .conjugate()),
      motion_tilt0_(prior.motion_tilt) {
  // Lambda = L L^T, so S = L^T gives S^T S = Lambda.
  const Matrix17d information =
      0.5 * (prior.information + prior.information.transpose()) + 1e-9 * Matrix17d::Identity();
  sqrt_information_ = Eigen::LLT<Matrix17d>(information).matrixU();
}

bool StatePriorFactor::Evaluate(double const* const* parameters, double* residuals,
                                double** jacobians) const {
  const double* pose = parameters[0];
  const Eigen::Quaterniond q(pose[6], pose[3], pose[4], pose[5]);
  const Eigen::Quaterniond dq = q * q0_inverse_;
  // q and -q are one rotation: the branch whose delta is small.
  const double sign = dq.w() < 0.0 ? -1.0 : 1.0;
  Vector17d e;
  e.head<3>() = Eigen::Vector3d(pose[0], pose[1], pose[2]) - p0_;
  e.segment<3>(3) = sign * dq.vec();
  e.segment<9>(6) = Eigen::Map<const Vector9d>(parameters[1]) - motion_tilt0_.head<9>();
  e.tail<2>() = Eigen::Map<const Eigen::Vector2d>(parameters[2]) - motion_tilt0_.tail<2>();
  Eigen::Map<Vector17d> r(residuals);
  r = sqrt_information_ * e;
  if (!jacobians) return true;
  if (jacobians[0]) {
    // vec(q b) with b = q0^-1 is linear in q = (x, y, z, w):
    //   x: ( b_w,  b_z, -b_y, b_x)   y: (-b_z,  b_w,  b_x, b_y)   z: ( b_y, -b_x,  b_w, b_z)
    const Eigen::Quaterniond& b = q0_inverse_;
    Eigen::Matrix<double, 3, 4> M;
    M << b.w(), b.z(), -b.y(), b.x(),  //
        -b.z(), b.w(), b.x(), b.y(),   //
        b.y(), -b.x(), b.w(), b.z();
    Eigen::Matrix<double, 6, 7> de_dpose = Eigen::Matrix<double, 6, 7>::Zero();
    de_dpose.topLeftCorner<3, 3>().setIdentity();
    de_dpose.bottomRightCorner<3, 4>() = sign * M;
    Eigen::Map<Eigen::Matrix<double, 17, 7, Eigen::RowMajor>> J(jacobians[0]);
    J = sqrt_information_.leftCols<6>() * de_dpose;
  }
  if (jacobians[1]) {
    Eigen::Map<Eigen::Matrix<double, 17, 9, Eigen::RowMajor>> J(jacobians[1]);
    J = sqrt_information_.middleCols<9>(6);
  }
  if (jacobians[2]) {
    Eigen::Map<Eigen::Matrix<double, 17, 2, Eigen::RowMajor>> J(jacobians[2]);
    J = sqrt_information_.rightCols<2>();
  }
  return true;
}

StatePrior propagateStatePrior(const StatePrior* prior_i, const MotionPrior& motion_prior_i,
                               const ImuGravityFactor& factor, const double* pose_i,
                               const double* motion_i, const double* pose_j, const double* motion_j,
                               const double* tilt,
                               const Eigen::Matrix<double, 6, 6>& lidar_information_i) {
  Eigen::Matrix<double, 32, 32> H =
      imuFactorInformation(factor, pose_i, motion_i, pose_j, motion_j, tilt);

  // State i's prior over [pose_i, motion_i, tilt] = z [0..14, 30..31].
  std::vector<int> prior_index(17);
  for (int k = 0; k < 15; ++k) prior_index[static_cast<std::size_t>(k)] = k;
  prior_index[15] = 30;
  prior_index[16] = 31;
  if (prior_i) {
    for (int a = 0; a < 17; ++a)
      for (int b = 0; b < 17; ++b)
        H(prior_index[static_cast<std::size_t>(a)], prior_index[static_cast<std::size_t>(b)]) +=
            prior_i->information(a, b);
  } else {
    for (int a = 0; a < 11; ++a)
      for (int b = 0; b < 11; ++b)
        H(prior_index[static_cast<std::size_t>(a + 6)],
          prior_index[static_cast<std::size_t>(b + 6)]) += motion_prior_i.information(a, b);
  }
  // LiDAR: the world tangent dtheta is 2 delta of the pose manifold's.
  Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Identity();
  T.bottomRightCorner<3, 3>() *= 2.0;
  H.topLeftCorner<6, 6>() += T.transpose() * lidar_information_i * T;

  // Marginalise pose_i (unless held fixed: then it is known, not a variable)
  // and motion_i onto z_15..31.
  const int first = prior_i ? 0 : 6;
  const int m = 15 - first;
  const Eigen::MatrixXd A = H.block(first, first, m, m);
  const Eigen::MatrixXd B = H.block(first, 15, m, 17);
  const Matrix17d C = H.bottomRightCorner<17, 17>();
  StatePrior prior_j;
  for (int k = 0; k < 7; ++k) prior_j.pose[k] = pose_j[k];
  prior_j.motion_tilt << Eigen::Map<const Vector9d>(motion_j),
      Eigen::Map<const Eigen::Vector2d>(tilt);
  prior_j.information = C - B.transpose() * A.ldlt().solve(B);
  prior_j.information = 0.5 * (prior_j.information + prior_j.information.transpose());
  return prior_j;
}

}  // namespace storey
