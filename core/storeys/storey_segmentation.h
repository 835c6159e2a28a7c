#pragma once
/// Storey segmentation of the registered map.
///
/// 1. The map is subsampled to StoreysConfig::voxel_size; PCA normals (CGAL)
///    are oriented towards the keyframe that observed each point.
/// 2. Planar regions: CGAL shape detection by region growing. Regions within
///    horizontal_angle_deg of horizontal and at least min_region_area large
///    are floor candidates (normal up) or ceiling candidates (normal down).
/// 3. Candidates are clustered by elevation into slabs (slab_tolerance). A
///    floor slab has >= min_floor_area; of floors closer than
///    min_storey_height the one stair flights start or end on is kept (a
///    split level: the main floor, not a larger wing a ramp higher), else the
///    larger (stair landings, table tops). A flight: consecutive keyframes
///    climbing steeper than 17 deg, at least 1 m in all; its end votes for the
///    highest floor slab within 1 m (xy) and 0.2-2.5 m below the sensor.
///    Floor elevation = median z of the slab's points (top of the slab).
/// 4. Ceiling of a storey: the largest downward slab between floor +
///    min_clear_height and the next floor (or floor + max_clear_height).
/// 5. Every map point gets the storey whose interval [floor - floor_tolerance,
///    next floor - floor_tolerance) holds its z (below the lowest: storey 0;
///    above the highest: the top storey). Stairwell: cells of a 2D grid that
///    hold upward-facing surfaces between two floors (steps, half landings)
///    near the keyframes where the sensor climbs; map points in those cells
///    between the two floors get the `stairs` flag (and the storey below).
/// 6. Footprint: CGAL 2D alpha shape of the storey's floor points, its
///    outer boundary as a polygon and the area of its interior.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/progress.h"
#include "map/map_cloud.h"
#include "storeys/storeys_config.h"

namespace storey {

struct StoreyInfo {
  int index = 0;                            ///< 0 = lowest
  double floor_elevation = 0.0;             ///< world z of the top of the floor slab [m]
  std::optional<double> ceiling_elevation;  ///< world z of the ceiling's underside [m]
  std::optional<double> height;            ///< floor to the next floor [m]; none for the top storey
  std::optional<double> clear_height;      ///< floor to ceiling [m]
  double floor_area_detected = 0.0;        ///< area of the floor slab's planar regions [m^2]
  double footprint_area = 0.0;             ///< area inside the footprint alpha shape [m^2]
  std::vector<Eigen::Vector2d> footprint;  ///< outer boundary, counter-clockwise, world x y [m]
  std::size_t points = 0;                  ///< map points labelled with this storey
  std::size_t stair_points = 0;            ///< of them, flagged as stairs
};

/// Why candidates were dropped (counts, for the report).
struct StoreySegmentationStats {
  std::size_t subsampled_points = 0;
  std::size_t regions = 0;             ///< planar regions found
  std::size_t floor_candidates = 0;    ///< upward horizontal regions >= min_region_area
  std::size_t ceiling_candidates = 0;  ///< downward horizontal regions >= min_region_area
  std::size_t floor_slabs = 0;         ///< elevation clusters of floor candidates
  std::size_t slabs_too_small = 0;     ///< rejected: area < min_floor_area
  std::size_t slabs_too_close = 0;     ///< rejected: within min_storey_height of a kept floor
  std::size_t stair_cells = 0;
  std::size_t flight_ends = 0;           ///< both ends of every stair flight of the keyframes
  std::size_t flight_ends_on_floor = 0;  ///< of them, standing on a floor slab (a vote)
  double usual_sensor_height = 0.0;      ///< the sensor above the floor off the flights [m]
  double seconds_normals = 0.0, seconds_regions = 0.0, seconds_labels = 0.0,
         seconds_footprints = 0.0;
};

struct StoreySegmentation {
  std::vector<StoreyInfo> storeys;  ///< bottom up
  StoreySegmentationStats stats;
};

/// Segments `map` (world frame, z up) and writes each point's storey and
/// flags (kMapPointStairs, kMapPointFloor) into it. `keyframe_positions`
/// (world position of the LiDAR at each keyframe index; may be empty) orient
/// the normals towards the sensor and locate the stairs. Points whose keyframe
/// has no position get normals with z >= 0 (their horizontal regions count as
/// floors), and stairs are then not gated by the trajectory. A map without a
/// floor slab gives no storeys and leaves every point kNoStorey.
StoreySegmentation segmentStoreys(MapCloud& map,
                                  const std::vector<Eigen::Vector3d>& keyframe_positions,
                                  const StoreysConfig& config, const ProgressFn& progress = {});

// ---- CGAL parts (storeys/cgal_*.cpp), exposed for tests ----

/// A planar region of a point set: indices of its points and its plane fit.
struct PlanarRegion {
  std::vector<std::size_t> indices;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, unoriented
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

/// Every point's nearest neighbours (itself among them, nearest first), found
/// once with CGAL's kd-tree (on every core; each point's list is CGAL's, in its
/// order) and shared by the normals and the region growing.
struct NearestNeighbours {
  std::size_t k = 0;                   ///< neighbours a point at most
  std::vector<std::uint32_t> count;    ///< per point (k, or fewer in a smaller set)
  std::vector<std::uint32_t> indices;  ///< point i's: [i * k, i * k + count[i])
};
NearestNeighbours findNearestNeighbours(const std::vector<Eigen::Vector3d>& points, std::size_t k);

/// PCA normals over each point's `neighbours.k` nearest points (what
/// CGAL::pca_estimate_normals computes with k - 1 neighbours, which it
/// counts without the point itself), unit, unoriented.
std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points,
                                             const NearestNeighbours& neighbours);
/// CGAL region growing on a point set with normals, over each point's first
/// `k` nearest neighbours (k <= neighbours.k), seeds in CGAL's order (the
/// least squares plane fit's score, computed on every core).
std::vector<PlanarRegion> detectPlanarRegions(const std::vector<Eigen::Vector3d>& points,
                                              const std::vector<Eigen::Vector3d>& normals,
                                              const NearestNeighbours& neighbours, std::size_t k,
                                              double max_distance, double max_angle_deg,
                                              std::size_t min_points);

struct Footprint {
  std::vector<Eigen::Vector2d> polygon;  ///< longest boundary loop, counter-clockwise
  double area = 0.0;                     ///< interior of the alpha shape [m^2]
};
/// CGAL 2D alpha shape (regularized) of `points` with radius `alpha` [m].
Footprint alphaShapeFootprint(const std::vector<Eigen::Vector2d>& points, double alpha);

}  // namespace storey
