// CGAL parts of the storey stage: PCA normals and planar regions by region
// growing (CGAL 5.5 Shape_detection, the index-based point-set API). Kept in
// this file (and cgal_footprint.cpp) so CGAL's compile cost and its
// -frounding-math stay out of the rest of storey_core.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing_on_point_set.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <cstdint>
#include <iterator>
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

/// The k nearest neighbours of every point, found once (in parallel; each
/// point's list is CGAL's K_neighbor_query's, in its order) and handed out
/// as often as asked: the seed sorting and the region growing both ask for
/// every point's.
class CachedNeighborQuery {
 public:
  template <typename Query>
  CachedNeighborQuery(const Query& query, std::size_t points, std::size_t k)
      : k_(k), count_(points, 0), neighbours_(points * k) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points, 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::vector<std::size_t> found;
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          query(i, found);
                          const std::size_t n = std::min(found.size(), k_);
                          for (std::size_t j = 0; j < n; ++j)
                            neighbours_[i * k_ + j] = static_cast<std::uint32_t>(found[j]);
                          count_[i] = static_cast<std::uint32_t>(n);
                        }
                      });
  }

  void operator()(std::size_t query_index, std::vector<std::size_t>& neighbors) const {
    neighbors.assign(
        neighbours_.begin() + static_cast<std::ptrdiff_t>(query_index * k_),
        neighbours_.begin() + static_cast<std::ptrdiff_t>(query_index * k_ + count_[query_index]));
  }

 private:
  std::size_t k_;
  std::vector<std::uint32_t> count_;
  std::vector<std::uint32_t> neighbours_;
};

}  // namespace

std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points,
                                             int neighbours) {
  std::vector<Eigen::Vector3d> normals;
  if (points.size() < 3) {
    normals.assign(points.size(), Eigen::Vector3d::UnitZ());
    return normals;
  }
  PointRange range = toRange(points, nullptr);
  const unsigned k = static_cast<unsigned>(
      std::min<std::size_t>(static_cast<std::size_t>(neighbours), points.size() - 1));
  CGAL::pca_estimate_normals<CGAL::Parallel_if_available_tag>(
      range, k, CGAL::parameters::point_map(PointMap()).normal_map(NormalMap()));
  normals.reserve(points.size());
  for (const PointNormal& pn : range) {
    Eigen::Vector3d n(pn.second.x(), pn.second.y(), pn.second.z());
    const double norm = n.norm();
    normals.push_back(norm > 0.0 && std::isfinite(norm) ? Eigen::Vector3d(n / norm)
                                                        : Eigen::Vector3d::UnitZ());
  }
  return normals;
}

std::vector<PlanarRegion> detectPlanarRegions(const std::vector<Eigen::Vector3d>& points,
                                              const std::vector<Eigen::Vector3d>& normals,
                                              int neighbours, double max_distance,
                                              double max_angle_deg, std::size_t min_points) {
  if (points.size() != normals.size()) throw Error("detectPlanarRegions: points/normals size");
  std::vector<PlanarRegion> out;
  if (points.size() < 3) return out;
  namespace SD = CGAL::Shape_detection;
  using KdTreeQuery = SD::Point_set::K_neighbor_query<Kernel, PointRange, PointMap>;
  using RegionType =
      SD::Point_set::Least_squares_plane_fit_region<Kernel, PointRange, PointMap, NormalMap>;
  using Sorting = SD::Point_set::Least_squares_plane_fit_sorting<Kernel, PointRange,
                                                                 CachedNeighborQuery, PointMap>;
  using RegionGrowing =
      SD::Region_growing<PointRange, CachedNeighborQuery, RegionType, Sorting::Seed_map>;

  const PointRange range = toRange(points, &normals);
  const std::size_t k =
      std::min<std::size_t>(static_cast<std::size_t>(neighbours), points.size() - 1);
  CachedNeighborQuery neighbor_query(KdTreeQuery(range, k, PointMap()), range.size(), k);
  RegionType region_type(range, max_distance, max_angle_deg, std::max<std::size_t>(min_points, 3),
                         PointMap(), NormalMap());
  Sorting sorting(range, neighbor_query, PointMap());
  sorting.sort();
  RegionGrowing region_growing(range, neighbor_query, region_type, sorting.seed_map());
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
