// The storey stage's normals and planar regions against CGAL's own
// pipeline: the shared nearest neighbours (found once, on every core) and the
// seed order computed on every core must give what CGAL::pca_estimate_normals
// and CGAL's region growing with its K_neighbor_query and
// Least_squares_plane_fit_sorting give, to the bit.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing_on_point_set.h>
#include <CGAL/pca_estimate_normals.h>
#include <gtest/gtest.h>

#include <random>

#include "storeys/storey_segmentation.h"

namespace storey {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using PointNormal = std::pair<Kernel::Point_3, Kernel::Vector_3>;
using PointRange = std::vector<PointNormal>;
using PointMap = CGAL::First_of_pair_property_map<PointNormal>;
using NormalMap = CGAL::Second_of_pair_property_map<PointNormal>;

/// A floor, two walls, a ramp and a stair's treads, 2 cm noise, shuffled.
std::vector<Eigen::Vector3d> scene() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 6000; ++i) {
    const double a = 6.0 * u(rng), b = 3.0 * u(rng);
    switch (i % 5) {
      case 0:
        points.emplace_back(a, 2.0 * b, noise(rng));
        break;
      case 1:
        points.emplace_back(a, noise(rng), b);
        break;
      case 2:
        points.emplace_back(noise(rng), 2.0 * b, b);
        break;
      case 3:
        points.emplace_back(a, 6.0 + b, 0.3 * a + noise(rng));
        break;
      default:
        points.emplace_back(3.0 + 0.3 * std::floor(b / 0.3) + 0.3 * u(rng), 8.0 + u(rng),
                            0.18 * std::floor(b / 0.3) + noise(rng));
    }
  }
  return points;
}

TEST(StoreysCgalReference, SharedNeighboursGiveCgalsNormalsAndRegions) {
  const std::vector<Eigen::Vector3d> points = scene();
  const std::size_t k = 12;
  const NearestNeighbours neighbours = findNearestNeighbours(points, k + 1);
  const std::vector<Eigen::Vector3d> normals = estimateNormals(points, neighbours);

  // CGAL's normals: pca_estimate_normals with k neighbours (and the point).
  PointRange range;
  for (const Eigen::Vector3d& p : points)
    range.emplace_back(Kernel::Point_3(p.x(), p.y(), p.z()), Kernel::Vector_3(0, 0, 1));
  CGAL::pca_estimate_normals<CGAL::Sequential_tag>(
      range, static_cast<unsigned>(k),
      CGAL::parameters::point_map(PointMap()).normal_map(NormalMap()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Kernel::Vector_3& v = range[i].second;
    const Eigen::Vector3d n = Eigen::Vector3d(v.x(), v.y(), v.z()).normalized();
    ASSERT_EQ(normals[i], n) << "point " << i;
  }

  // CGAL's region growing with its own neighbour query and seed sorting.
  for (std::size_t i = 0; i < points.size(); ++i)
    range[i].second = Kernel::Vector_3(normals[i].x(), normals[i].y(), normals[i].z());
  namespace SD = CGAL::Shape_detection;
  using Query = SD::Point_set::K_neighbor_query<Kernel, PointRange, PointMap>;
  using Region =
      SD::Point_set::Least_squares_plane_fit_region<Kernel, PointRange, PointMap, NormalMap>;
  using Sorting =
      SD::Point_set::Least_squares_plane_fit_sorting<Kernel, PointRange, Query, PointMap>;
  Query query(range, k, PointMap());
  Region region(range, 0.05, 15.0, 20, PointMap(), NormalMap());
  Sorting sorting(range, query, PointMap());
  sorting.sort();
  SD::Region_growing<PointRange, Query, Region, Sorting::Seed_map> growing(range, query, region,
                                                                           sorting.seed_map());
  std::vector<std::vector<std::size_t>> expected;
  growing.detect(std::back_inserter(expected));

  const std::vector<PlanarRegion> regions =
      detectPlanarRegions(points, normals, neighbours, k, 0.05, 15.0, 20);
  ASSERT_GE(expected.size(), 5u);
  ASSERT_EQ(regions.size(), expected.size());
  for (std::size_t r = 0; r < regions.size(); ++r) EXPECT_EQ(regions[r].indices, expected[r]) << r;
}

}  // namespace
}  // namespace storey
