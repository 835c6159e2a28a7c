#include "backend/odometry_information.h"

#include <cmath>

namespace storey::backend {

OdometryEdgeSigma odometryEdgeSigma(const GraphConfig& g, const Pose& T_odom_a,
                                    const Pose& T_odom_b) {
  const Pose T_a_b = T_odom_a.inverse() * T_odom_b;
  const double distance = T_a_b.translation().norm();
  const double angle = T_a_b.angle();
  const double climbed = std::abs(T_odom_b.translation().z() - T_odom_a.translation().z());
  OdometryEdgeSigma s;
  s.translation = g.odometry_sigma_translation + g.odometry_sigma_translation_per_m * distance +
                  g.odometry_sigma_translation_per_rad * angle +
                  g.odometry_sigma_translation_per_m_climbed * climbed;
  s.rotation = g.odometry_sigma_rotation + g.odometry_sigma_rotation_per_m * distance +
               g.odometry_sigma_rotation_per_rad * angle +
               g.odometry_sigma_rotation_per_m_climbed * climbed;
  return s;
}

Eigen::Matrix<double, 6, 6> odometryEdgeInformation(const GraphConfig& g, const Pose& T_odom_a,
                                                    const Pose& T_odom_b) {
  const OdometryEdgeSigma s = odometryEdgeSigma(g, T_odom_a, T_odom_b);
  const double wt = 1.0 / (s.translation * s.translation);
  const double wr = 1.0 / (s.rotation * s.rotation);
  Eigen::Matrix<double, 6, 1> diag;
  diag << wt, wt, wt, wr, wr, wr;
  return diag.asDiagonal();
}

}  // namespace storey::backend
