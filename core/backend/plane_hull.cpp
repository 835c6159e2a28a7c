#include "backend/plane_hull.h"

#include <algorithm>

#include "backend/plane_math.h"

namespace storey::backend {

namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

}  // namespace

std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> p) {
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
