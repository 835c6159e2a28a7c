// CGAL parts of the storey stage: nearest neighbours, PCA normals and planar
// regions by region growing (CGAL 5.5 Shape_detection, the index-based point-set API). Kept in
// this file (and cgal_footprint.cpp) so CGAL's compile cost and its
// -frounding-math stay out of the rest of storey_core.
#include <CGAL/Eigen_diagonalize_traits.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing_on_point_set.h>
#include <CGAL/linear_least_squares_fitting_3.h>
#include <CGAL/property_map.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>
#include <utility>

#include "common/error.h"
#include "storeys/storey_segmentation.h"

namespace storey {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using Vector3 = Kernel::Vector_3;
using PointNormal = std::pair<Point3, Vector3>;
using PointRange = std::vector<PointNormal>;
using PointMap = CGAL::First_of_pair_property_map<PointNormal>;
using NormalMap = CGAL::Second_of_pair_property_map<PointNormal>;

PointRange toRange(const std::vector<Eigen::Vector3d>& points,
                   const std::vector<Eigen::Vector3d>* normals) {
  PointRange range;
  range.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d n = normals ? (*normals)[i] : Eigen::Vector3d::UnitZ();
    range.emplace_back(Point3(points[i].x(), points[i].y(), points[i].z()),
                       Vector3(n.x(), n.y(), n.z()));
  }
  return range;
}

/// Region growing's neighbour query: a point's first k of its shared
/// nearest neighbours, as often as asked (the seed scores and the growing
/// both ask for every point's).
class SharedNeighborQuery {
 public:
  SharedNeighborQuery(const NearestNeighbours& neighbours, std::size_t k)
      : neighbours_(neighbours), k_(k) {}

  void operator()(std::size_t query_index, std::vector<std::size_t>& neighbors) const {
    const auto first =
        neighbours_.indices.begin() + static_cast<std::ptrdiff_t>(query_index * neighbours_.k);
    const std::size_t n = std::min<std::size_t>(neighbours_.count[query_index], k_);
    neighbors.assign(first, first + static_cast<std::ptrdiff_t>(n));
  }

 private:
  const NearestNeighbours& neighbours_;
  std::size_t k_;
};

/// The seeds' order, as a readable property map (seed number -> point).
class SeedOrder {
 public:
  using key_type = std::size_t;
  using value_type = std::size_t;
  using category = boost::readable_property_map_tag;
  explicit SeedOrder(const std::vector<std::size_t>& order) : order_(&order) {}
  friend value_type get(const SeedOrder& map, key_type key) { return (*map.order_)[key]; }

 private:
  const std::vector<std::size_t>* order_;
};

/// CGAL's seed order for plane region growing
/// (Least_squares_plane_fit_sorting): points by decreasing quality of the
/// least squares plane through their neighbours and themselves, the same
/// computation per point, here on every core.
std::vector<std::size_t> seedOrder(const PointRange& range, const SharedNeighborQuery& query) {
  std::vector<double> scores(range.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, range.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& block) {
                      std::vector<std::size_t> neighbors;
                      std::vector<Point3> points;
                      for (std::size_t i = block.begin(); i != block.end(); ++i) {
                        query(i, neighbors);
                        neighbors.push_back(i);
                        points.clear();
                        for (std::size_t j : neighbors) points.push_back(range[j].first);
                        Kernel::Plane_3 plane;
                        Point3 centroid;
                        scores[i] = CGAL::linear_least_squares_fitting_3(
                            points.begin(), points.end(), plane, centroid, CGAL::Dimension_tag<0>(),
                            Kernel(), CGAL::Eigen_diagonalize_traits<double, 3>());
                      }
                    });
  std::vector<std::size_t> order(range.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&scores](std::size_t a, std::size_t b) { return scores[a] > scores[b]; });
  return order;
}

}  // namespace

NearestNeighbours findNearestNeighbours(const std::vector<Eigen::Vector3d>& points, std::size_t k) {
  NearestNeighbours out;
  if (points.empty() || k == 0) return out;
  if (points.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error("findNearestNeighbours: more than 2^32 points");
  const PointRange range = toRange(points, nullptr);
  using KdTreeQuery =
      CGAL::Shape_detection::Point_set::K_neighbor_query<Kernel, PointRange, PointMap>;
  const KdTreeQuery query(range, k, PointMap());
  out.k = k;
  out.count.assign(points.size(), 0);
  out.indices.assign(points.size() * k, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& block) {
                      std::vector<std::size_t> found;
                      for (std::size_t i = block.begin(); i != block.end(); ++i) {
                        query(i, found);
                        const std::size_t n = std::min(found.size(), k);
                        for (std::size_t j = 0; j < n; ++j)
                          out.indices[i * k + j] = static_cast<std::uint32_t>(found[j]);
                        out.count[i] = static_cast<std::uint32_t>(n);
                      }
                    });
  return out;
}

std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points,
                                             const NearestNeighbours& neighbours) {
  if (neighbours.count.size() != points.size())
    throw Error("estimateNormals: neighbours of another point set");
  std::vector<Eigen::Vector3d> normals(points.size(), Eigen::Vector3d::UnitZ());
  if (points.size() < 3) return normals;
  // As CGAL::pca_estimate_normal: a plane fitted by point-based PCA to the
  // neighbours in their order, its orthogonal vector.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& block) {
                      std::vector<Point3> nearest;
                      for (std::size_t i = block.begin(); i != block.end(); ++i) {
                        nearest.clear();
                        for (std::uint32_t j = 0; j < neighbours.count[i]; ++j) {
                          const Eigen::Vector3d& p =
                              points[neighbours.indices[i * neighbours.k + j]];
                          nearest.emplace_back(p.x(), p.y(), p.z());
                        }
                        Kernel::Plane_3 plane;
                        CGAL::linear_least_squares_fitting_3(nearest.begin(), nearest.end(), plane,
                                                             CGAL::Dimension_tag<0>());
                        const Vector3 v = plane.orthogonal_vector();
                        const Eigen::Vector3d n(v.x(), v.y(), v.z());
                        const double norm = n.norm();
                        if (norm > 0.0 && std::isfinite(norm)) normals[i] = n / norm;
                      }
                    });
  return normals;
}

std::vector<PlanarRegion> detectPlanarRegions(const std::vector<Eigen::Vector3d>& points,
                                              const std::vector<Eigen::Vector3d>& normals,
                                              const NearestNeighbours& neighbours, std::size_t k,
                                              double max_distance, double max_angle_deg,
                                              std::size_t min_points) {
  if (points.size() != normals.size()) throw Error("detectPlanarRegions: points/normals size");
  if (neighbours.count.size() != points.size() || k > neighbours.k)
    throw Error("detectPlanarRegions: neighbours of another point set");
  std::vector<PlanarRegion> out;
  if (points.size() < 3) return out;
  namespace SD = CGAL::Shape_detection;
  using RegionType =
      SD::Point_set::Least_squares_plane_fit_region<Kernel, PointRange, PointMap, NormalMap>;
  using RegionGrowing = SD::Region_growing<PointRange, SharedNeighborQuery, RegionType, SeedOrder>;

  const PointRange range = toRange(points, &normals);
  SharedNeighborQuery neighbor_query(neighbours, k);
  RegionType region_type(range, max_distance, max_angle_deg, std::max<std::size_t>(min_points, 3),
                         PointMap(), NormalMap());
  const std::vector<std::size_t> order = seedOrder(range, neighbor_query);
  RegionGrowing region_growing(range, neighbor_query, region_type, SeedOrder(order));
  std::vector<std::vector<std::size_t>> regions;
  region_growing.detect(std::back_inserter(regions));

  out.reserve(regions.size());
  for (auto& indices : regions) {
    PlanarRegion region;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (std::size_t i : indices) c += points[i];
    c /= static_cast<double>(indices.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t i : indices) {
      const Eigen::Vector3d d = points[i] - c;
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    region.normal = solver.eigenvectors().col(0).normalized();
    region.centroid = c;
    region.indices = std::move(indices);
    out.push_back(std::move(region));
  }
  return out;
}

}  // namespace storey
