#pragma once
/// Where a plane landmark has been seen: a rectangle on the plane that holds
/// the outlines (hulls) of its observations, in two fixed in-plane directions
/// (the tangent basis of its normal when it was made). The association uses
/// it so that a landmark is only a candidate where it has been seen: a
/// landmark is an infinite plane, and two parallel walls a few centimetres
/// apart at two ends of a building (a stairwell wall and a corridor wall)
/// would otherwise be one landmark whose keyframes are pulled onto both
/// (docs/method/backend.md, "Landmarks are where they were seen").
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "backend/plane_math.h"

namespace storey::backend {

struct PlaneExtent {
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();  ///< in-plane directions (unit, orthogonal)
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();
  /// The rectangle: coordinates p . axis_u in [lo.x, hi.x], p . axis_v in
  /// [lo.y, hi.y] [m]; lo > hi while nothing has been added.
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity());

  PlaneExtent() = default;
  /// An empty extent of a plane with unit normal `n` (its frame's directions).
  explicit PlaneExtent(const Eigen::Vector3d& n) {
    const Eigen::Matrix<double, 3, 2> B = tangentBasis(n);
    axis_u = B.col(0);
    axis_v = B.col(1);
  }

  bool empty() const { return !(lo.x() <= hi.x()); }

  /// Grows the rectangle to hold `points` (same frame as the axes).
  void add(const std::vector<Eigen::Vector3d>& points) {
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector2d c(p.dot(axis_u), p.dot(axis_v));
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
  }

  /// The same rectangle in a frame `b` with T_a_b = (R_a_b, t_a_b), this
  /// extent in frame a: axes rotated, bounds shifted by the origin's offset.
  PlaneExtent inFrame(const Eigen::Matrix3d& R_a_b, const Eigen::Vector3d& t_a_b) const {
    PlaneExtent out = *this;
    out.axis_u = R_a_b.transpose() * axis_u;
    out.axis_v = R_a_b.transpose() * axis_v;
    const Eigen::Vector2d shift(t_a_b.dot(axis_u), t_a_b.dot(axis_v));
    out.lo -= shift;
    out.hi -= shift;
    return out;
  }

  /// Distance between the rectangle and the rectangle (in the same two
  /// directions) holding `points` [m]: 0 when they overlap; 0 when either is
  /// empty (nothing known: no test).
  double gap(const std::vector<Eigen::Vector3d>& points) const {
    if (empty() || points.empty()) return 0.0;
    PlaneExtent other = *this;
    other.lo.setConstant(std::numeric_limits<double>::infinity());
    other.hi.setConstant(-std::numeric_limits<double>::infinity());
    other.add(points);
    const Eigen::Vector2d g =
        (other.lo - hi).cwiseMax(lo - other.hi).cwiseMax(Eigen::Vector2d::Zero());
    return g.norm();
  }
};

}  // namespace storey::backend
