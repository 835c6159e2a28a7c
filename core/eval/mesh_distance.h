#pragma once
/// Unsigned distance from points to a triangle mesh, with CGAL's AABB tree
/// (the only file of the evaluation stage that includes CGAL).
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace storey::eval {

class MeshDistance {
 public:
  /// Builds the tree over the triangles (indices into `vertices`); degenerate
  /// triangles are dropped. Throws storey::Error when no triangle is left.
  MeshDistance(const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<std::uint32_t, 3>>& triangles);
  ~MeshDistance();
  MeshDistance(const MeshDistance&) = delete;
  MeshDistance& operator=(const MeshDistance&) = delete;

  std::size_t triangles() const;
  /// Distance from x to the nearest triangle [m].
  double distance(const Eigen::Vector3d& x) const;
  /// Distances of all points, computed on `threads` threads (0 = all cores) [m].
  std::vector<double> distances(const std::vector<Eigen::Vector3d>& points, int threads = 0) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace storey::eval
