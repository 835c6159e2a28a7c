// CGAL part of the storey stage: the footprint of a floor as a 2D alpha shape.
#include <CGAL/Alpha_shape_2.h>
#include <CGAL/Alpha_shape_face_base_2.h>
#include <CGAL/Alpha_shape_vertex_base_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "storeys/storey_segmentation.h"

namespace storey {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using Vb = CGAL::Alpha_shape_vertex_base_2<Kernel>;
using Fb = CGAL::Alpha_shape_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Triangulation = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using AlphaShape = CGAL::Alpha_shape_2<Triangulation>;

double signedArea(const std::vector<Eigen::Vector2d>& ring) {
  double a = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& p = ring[i];
    const Eigen::Vector2d& q = ring[(i + 1) % ring.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

}  // namespace

Footprint alphaShapeFootprint(const std::vector<Eigen::Vector2d>& points, double alpha) {
  Footprint result;
  if (points.size() < 3) return result;
  std::vector<Point2> cgal_points;
  cgal_points.reserve(points.size());
  for (const Eigen::Vector2d& p : points) cgal_points.emplace_back(p.x(), p.y());
  AlphaShape shape(cgal_points.begin(), cgal_points.end(), AlphaShape::FT(alpha * alpha),
                   AlphaShape::REGULARIZED);

  for (auto f = shape.finite_faces_begin(); f != shape.finite_faces_end(); ++f) {
    if (shape.classify(f) != AlphaShape::INTERIOR) continue;
    result.area += std::abs(CGAL::to_double(
        CGAL::area(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point())));
  }

  // Boundary edges oriented with the interior on their left, chained into
  // loops. Vertices are ordered by their coordinates, not by their handles'
  // addresses, so the loops (and where each starts) are the same on every run.
  using Vertex = AlphaShape::Vertex_handle;
  struct ByPoint {
    bool operator()(const Vertex& a, const Vertex& b) const {
      return CGAL::compare_xy(a->point(), b->point()) == CGAL::SMALLER;
    }
  };
  std::multimap<Vertex, Vertex, ByPoint> next;
  for (auto e = shape.alpha_shape_edges_begin(); e != shape.alpha_shape_edges_end(); ++e) {
    AlphaShape::Face_handle f = e->first;
    int i = e->second;
    if (shape.is_infinite(f) || shape.classify(f) != AlphaShape::INTERIOR) {
      const AlphaShape::Face_handle g = f->neighbor(i);
      i = g->index(f);
      f = g;
    }
    next.emplace(f->vertex(AlphaShape::ccw(i)), f->vertex(AlphaShape::cw(i)));
  }
  std::vector<Eigen::Vector2d> best;
  double best_area = 0.0;
  while (!next.empty()) {
    const Vertex start = next.begin()->first;
    std::vector<Eigen::Vector2d> ring;
    Vertex v = start;
    while (true) {
      auto it = next.find(v);
      if (it == next.end()) break;
      ring.emplace_back(CGAL::to_double(v->point().x()), CGAL::to_double(v->point().y()));
      const Vertex w = it->second;
      next.erase(it);
      v = w;
      if (v == start) break;
    }
    const double a = signedArea(ring);
    if (ring.size() >= 3 && std::abs(a) > best_area) {
      best_area = std::abs(a);
      best = std::move(ring);
    }
  }
  if (signedArea(best) < 0.0) std::reverse(best.begin(), best.end());
  result.polygon = std::move(best);
  return result;
}

}  // namespace storey
