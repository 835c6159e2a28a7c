#include "backend/plane_hull.h"

#include <algorithm>
#include <limits>

#include "backend/plane_math.h"

namespace storey::backend {

namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

/// Akl-Toussaint: a point strictly inside the polygon of the extreme points
/// (least and greatest x, y, x + y and x - y: an octagon) is no hull vertex.
/// Dropping those before the sort leaves the hull unchanged and the sort
/// short (a plane's inliers are thousands of points, its hull a few dozen).
/// Points within a small margin of the polygon's sides are kept, so rounding
/// decides nothing.
void dropInteriorPoints(std::vector<Eigen::Vector2d>& p) {
  if (p.size() < 16) return;
  // Directions counter-clockwise from -y: the extreme value along each...
  const double dirs[8][2] = {{0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}};
  double best_value[8];
  for (int e = 0; e < 8; ++e) best_value[e] = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& q : p)
    for (int e = 0; e < 8; ++e)
      best_value[e] = std::max(best_value[e], dirs[e][0] * q.x() + dirs[e][1] * q.y());
  // ... and the first point that has it: the octagon's corners, a corner
  // extreme in two directions once.
  Eigen::Vector2d corner[8];
  int corners = 0;
  for (int e = 0; e < 8; ++e) {
    std::size_t i = 0;
    while (dirs[e][0] * p[i].x() + dirs[e][1] * p[i].y() != best_value[e]) ++i;
    if (corners == 0 || p[i] != corner[corners - 1]) corner[corners++] = p[i];
  }
  while (corners > 1 && corner[corners - 1] == corner[0]) --corners;
  if (corners < 3) return;
  const double span = (best_value[2] + best_value[6]) + (best_value[4] + best_value[0]);
  if (!(span > 0.0)) return;
  // Side e keeps q on its left: a_e x + b_e y > c_e (a margin of rounding
  // above the line through its corners: cross products are lengths squared).
  const double margin = 1e-9 * span * span;
  double a[8], b[8], c[8];
  for (int e = 0; e < corners; ++e) {
    const Eigen::Vector2d& o = corner[e];
    const Eigen::Vector2d& t = corner[(e + 1) % corners];
    a[e] = -(t.y() - o.y());
    b[e] = t.x() - o.x();
    c[e] = a[e] * o.x() + b[e] * o.y() + margin;
  }
  const auto strictlyInside = [&](const Eigen::Vector2d& q) {
    for (int e = 0; e < corners; ++e)
      if (!(a[e] * q.x() + b[e] * q.y() > c[e])) return false;
    return true;
  };
  p.erase(std::remove_if(p.begin(), p.end(), strictlyInside), p.end());
}

}  // namespace

std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> p) {
  dropInteriorPoints(p);
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return {};
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0) --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);  // the last point repeats the first
  if (hull.size() < 3) return {};
  return hull;
}

std::vector<Eigen::Vector3d> planeHull(const std::vector<Eigen::Vector3d>& points,
                                       const Plane& plane, int max_vertices) {
  const Eigen::Vector3d n = plane.normal();
  const Eigen::Matrix<double, 3, 2> B = tangentBasis(n);
  // Right-handed (b1, b2, n), so counter-clockwise in (b1, b2) is counter-clockwise seen from +n.
  Eigen::Matrix<double, 3, 2> basis = B;
  if (B.col(0).cross(B.col(1)).dot(n) < 0) basis.col(1) = -B.col(1);
  const Eigen::Vector3d origin = plane.distance() * n;
  std::vector<Eigen::Vector2d> flat;
  flat.reserve(points.size());
  for (const Eigen::Vector3d& p : points) flat.push_back(basis.transpose() * (p - origin));
  std::vector<Eigen::Vector2d> hull = convexHull(std::move(flat));
  const std::size_t limit = static_cast<std::size_t>(std::max(3, max_vertices));
  while (hull.size() > limit) {
    // Visvalingam: drop the vertex spanning the smallest triangle with its neighbours.
    std::size_t best = 0;
    double best_area = 0.0;
    for (std::size_t i = 0; i < hull.size(); ++i) {
      const auto& a = hull[(i + hull.size() - 1) % hull.size()];
      const auto& c = hull[(i + 1) % hull.size()];
      const double area = std::abs(cross(a, hull[i], c));
      if (i == 0 || area < best_area) {
        best = i;
        best_area = area;
      }
    }
    hull.erase(hull.begin() + static_cast<std::ptrdiff_t>(best));
  }
  std::vector<Eigen::Vector3d> out;
  out.reserve(hull.size());
  for (const Eigen::Vector2d& q : hull) out.push_back(origin + basis * q);
  return out;
}

}  // namespace storey::backend
