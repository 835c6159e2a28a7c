#include "eval/mesh_distance.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.h"

namespace storey::eval {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using CgalTriangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<CgalTriangle>::const_iterator>;
using Traits = CGAL::AABB_traits<Kernel, Primitive>;
using AabbTree = CGAL::AABB_tree<Traits>;

Point toCgal(const Eigen::Vector3d& x) {
  return Point(x.x(), x.y(), x.z());
}
}  // namespace

struct MeshDistance::Tree {
  std::vector<CgalTriangle> triangles;  // owned here: the primitives point into it
  AabbTree tree;
};

MeshDistance::MeshDistance(const std::vector<Eigen::Vector3d>& vertices,
                           const std::vector<std::array<std::uint32_t, 3>>& triangles)
    : tree_(std::make_unique<Tree>()) {
  tree_->triangles.reserve(triangles.size());
  for (const auto& t : triangles) {
    for (std::uint32_t i : t)
      if (i >= vertices.size()) throw Error("eval: mesh triangle refers to a missing vertex");
    const CgalTriangle triangle(toCgal(vertices[t[0]]), toCgal(vertices[t[1]]),
                                toCgal(vertices[t[2]]));
    if (!triangle.is_degenerate()) tree_->triangles.push_back(triangle);
  }
  if (tree_->triangles.empty()) throw Error("eval: the mesh has no non-degenerate triangle");
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
  // Built now, not lazily at the first query, so that queries from several threads only read.
  tree_->tree.accelerate_distance_queries();
}

MeshDistance::~MeshDistance() = default;

std::size_t MeshDistance::triangles() const {
  return tree_->triangles.size();
}

double MeshDistance::distance(const Eigen::Vector3d& x) const {
  return std::sqrt(tree_->tree.squared_distance(toCgal(x)));
}

namespace {

/// Interleaves the low 21 bits of x, y and z (Morton order).
std::uint64_t mortonCode(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  auto spread = [](std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  return spread(x) | spread(y) << 1 | spread(z) << 2;
}

/// Point indices in Morton order over the points' bounding box, so that
/// consecutive queries are close and each can start from the last answer.
std::vector<std::uint32_t> spatialOrder(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double scale = static_cast<double>((1u << 21) - 1) / std::max((hi - lo).maxCoeff(), 1e-9);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d c = (points[i] - lo) * scale;
    keyed[i] = {mortonCode(static_cast<std::uint32_t>(c.x()), static_cast<std::uint32_t>(c.y()),
                           static_cast<std::uint32_t>(c.z())),
                static_cast<std::uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(points.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace

std::vector<double> MeshDistance::distances(const std::vector<Eigen::Vector3d>& points,
                                            int threads) const {
  std::vector<double> result(points.size());
  if (points.empty()) return result;
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw Error("eval: too many points for one distance query (4 billion)");
  const std::vector<std::uint32_t> order = spatialOrder(points);
  const AabbTree& tree = tree_->tree;
  auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        // The previous answer is a hint: it bounds the search to a small ball.
                        Point hint = tree.closest_point(toCgal(points[order[range.begin()]]));
                        for (std::size_t k = range.begin(); k != range.end(); ++k) {
                          const Point query = toCgal(points[order[k]]);
                          hint = tree.closest_point(query, hint);
                          result[order[k]] = std::sqrt(CGAL::squared_distance(query, hint));
                        }
                      });
  };
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute(run);
  } else {
    run();
  }
  return result;
}

}  // namespace storey::eval
