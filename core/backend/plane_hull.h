#pragma once
/// The outline of a detected plane: the convex hull of its inlier points
/// projected onto the plane, simplified to a few vertices. Renders and the
/// CloudCompare plugin draw SRPs as these patches (planes.json "hull").
#include <Eigen/Core>
#include <vector>

#include "types/plane.h"

namespace storey::backend {

/// Convex hull of points in a plane (Andrew's monotone chain):
/// counter-clockwise, no collinear vertices; empty for fewer than 3
/// distinct, non-collinear points.
std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> points);

/// Convex hull of `points` projected onto `plane`, counter-clockwise seen
/// from the side the normal points to, as 3D points on the plane (same frame
/// as the input). When the hull has more than `max_vertices` (>= 3) vertices,
/// the ones whose removal loses the least area go first (Visvalingam). Fewer
/// than 3 distinct points give an empty hull.
std::vector<Eigen::Vector3d> planeHull(const std::vector<Eigen::Vector3d>& points,
                                       const Plane& plane, int max_vertices = 16);

}  // namespace storey::backend
