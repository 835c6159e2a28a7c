#pragma once
/// Views of level surfaces that are not level under the solved poses.
///
/// A floor or ceiling landmark (its normal within level_tolerance of
/// vertical: the landmarks that get the level prior) is level, and so is
/// every right view of it, placed with its keyframe's solved pose, to within
/// the fit's and the attitude's errors (on development seed 26 1.2 mrad
/// median, 2.5 mrad at the 90th percentile). A view tilted by several
/// milliradians is a mixed fit: a ceiling patch seen from the stairs that
/// takes in the underside of a flight, a floor band across a tread or a
/// slab edge. Such views enter the whole-graph solves with an uncertainty
/// that knows only their point count and RMS, and the graph bends its
/// keyframes to fit them (docs/benchmarks.md, session 27).
#include <Eigen/Core>
#include <cmath>

namespace storey::backend {

/// True when the normal `n` is within `tolerance_rad` of vertical (up or
/// down): the floors and ceilings that get the level prior (plane_graph.cpp).
inline bool isNearlyLevel(const Eigen::Vector3d& n, double tolerance_rad) {
  const Eigen::Vector3d u = n.normalized();
  return std::hypot(u.x(), u.y()) < std::sin(tolerance_rad);
}

/// True when `n_landmark_world` is within `level_tolerance_rad` of vertical
/// (a floor or ceiling) and the view's normal in the world,
/// `n_view_world` (the observed normal turned by its keyframe's solved
/// attitude), is farther than `max_tilt_rad` from vertical. Either normal may
/// point up or down; `max_tilt_rad` <= 0 turns the test off.
inline bool isTiltedLevelView(const Eigen::Vector3d& n_landmark_world,
                              const Eigen::Vector3d& n_view_world, double level_tolerance_rad,
                              double max_tilt_rad) {
  if (max_tilt_rad <= 0.0) return false;
  if (!isNearlyLevel(n_landmark_world, level_tolerance_rad)) return false;
  const Eigen::Vector3d v = n_view_world.normalized();
  return std::atan2(std::hypot(v.x(), v.y()), std::abs(v.z())) > max_tilt_rad;
}

}  // namespace storey::backend
