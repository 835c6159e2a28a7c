#pragma once
/// Information (inverse covariance) of an odometry edge between consecutive
/// keyframes a and b of the graph (docs/method/backend.md, relative-pose
/// factor). The odometry's error per edge is not a fixed share of the distance:
/// on the development seeds it is a few millimetres on straight level walking
/// and three to four times that where the front end is weak, on turns (the
/// half-landings of stairs) and while climbing. So each standard deviation is
///   sigma = base + per_m * distance + per_rad * angle turned + per_m_climbed * |height change|,
/// isotropic in translation and in rotation, with the residual's layout
/// (translation in frame a, then rotation).
#include <Eigen/Core>

#include "backend/backend_config.h"
#include "types/pose.h"

namespace storey::backend {

/// Standard deviations of one edge [m, rad].
struct OdometryEdgeSigma {
  double translation = 0.0;
  double rotation = 0.0;
};

/// The edge's sigmas from its odometry poses (the odometry's frame is
/// gravity-aligned: its z is the height).
OdometryEdgeSigma odometryEdgeSigma(const GraphConfig& config, const Pose& T_odom_a,
                                    const Pose& T_odom_b);

/// diag(1/sigma_t^2 I3, 1/sigma_r^2 I3) of that edge.
Eigen::Matrix<double, 6, 6> odometryEdgeInformation(const GraphConfig& config, const Pose& T_odom_a,
                                                    const Pose& T_odom_b);

}  // namespace storey::backend
