#pragma once
/// The odometry's local map: points in the world frame kept in a hash of
/// cubic voxels (at most `max_points_per_voxel` each, spread at least
/// `min_point_spacing` apart), queried for the k nearest neighbours of a
/// point among the 27 voxels around it. Voxels far from the sensor are
/// dropped, so memory is bounded by the map's extent around the sensor, not
/// by the log's length (the idea of iVox, Faster-LIO, and of KISS-ICP's map).
///
/// Each point may keep the unit direction from it towards the sensor that
/// observed it (its view direction). A surface is seen from one side only:
/// the two faces of a floor slab or of a wall are parallel planes a slab or a
/// wall thickness apart, and without the view direction a point on one face
/// cannot be told from a point on the other (scan_matcher.h).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "types/pose.h"

namespace storey {

struct VoxelMapConfig {
  double voxel_size = 0.5;         ///< voxel edge [m]
  int max_points_per_voxel = 20;   ///< points kept per voxel [>= 1]
  double min_point_spacing = 0.1;  ///< a new point closer than this to a kept one is skipped [m]
  double max_range = 60.0;         ///< voxels farther than this from the sensor are dropped [m]
};

class VoxelMap {
 public:
  explicit VoxelMap(const VoxelMapConfig& config);

  /// Adds points (world frame) without a view direction (stored as zero).
  void insert(const std::vector<Eigen::Vector3f>& points_world);
  /// Adds points (world frame) observed from `sensor_world`: each keeps its
  /// unit direction towards the sensor.
  void insert(const std::vector<Eigen::Vector3f>& points_world,
              const Eigen::Vector3d& sensor_world);
  /// Drops every voxel whose centre is farther than config.max_range from `sensor_world`.
  void removeFar(const Eigen::Vector3d& sensor_world);

  /// Up to k nearest neighbours of `query` within `max_distance` [m], nearest
  /// first. Searches the 27 voxels around the query, so max_distance should
  /// not exceed the voxel size.
  std::vector<Eigen::Vector3f> nearest(const Eigen::Vector3f& query, int k,
                                       float max_distance) const;
  /// Same without allocation: writes up to min(k, kMaxNeighbours) points to
  /// `out`, nearest first, and returns how many; with `views_out`, also their
  /// view directions (zero when unknown).
  static constexpr int kMaxNeighbours = 16;
  int nearest(const Eigen::Vector3f& query, int k, float max_distance, Eigen::Vector3f* out,
              Eigen::Vector3f* views_out = nullptr) const;

  /// Maps every point by T (x -> T * x, views rotated) and rebuilds the hash.
  void transform(const Pose& T);

  std::size_t pointCount() const { return point_count_; }
  std::size_t voxelCount() const { return voxel_count_; }
  bool empty() const { return point_count_ == 0; }

 private:
  using Key = std::uint64_t;
  Key keyOf(const Eigen::Vector3f& p) const;
  Key keyOf(std::int64_t x, std::int64_t y, std::int64_t z) const;
  Eigen::Vector3i cellOf(const Eigen::Vector3f& p) const;
  struct MapPoint {
    Eigen::Vector3f p;
    Eigen::Vector3f view;  ///< unit direction towards the observing sensor, or zero
  };
  /// A slot of the open-addressing index: a voxel's key, where its points
  /// are (a block of capacity_ in points_) and how many it holds.
  struct Slot {
    Key key;
    std::uint32_t block;
    std::uint32_t count;
  };
  static constexpr Key kEmptyKey = ~Key{0};
  const Slot* findSlot(Key key) const;
  Slot& findOrAddSlot(Key key);
  void rebuildIndex(std::size_t slots);
  void insertPoint(const Eigen::Vector3f& p, const Eigen::Vector3f& view);

  VoxelMapConfig config_;
  float inverse_size_;
  std::size_t capacity_;                    ///< points per voxel (block size)
  std::vector<Slot> slots_;                 ///< power-of-two size, at most half full
  std::vector<MapPoint> points_;            ///< blocks of capacity_ points
  std::vector<Key> block_keys_;             ///< per block: its voxel's key, or kEmptyKey when free
  std::vector<std::uint32_t> free_blocks_;  ///< blocks of dropped voxels, reused first
  std::size_t voxel_count_ = 0;
  std::size_t point_count_ = 0;
};

/// Plane n . x = d fitted to points (least squares by PCA); `valid` only when
/// every point lies within `max_distance` of it and the points spread in two
/// directions (second eigenvalue at least 1 % of the largest: not a line).
struct PlaneFit {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double d = 0.0;
  double thickness = 0.0;  ///< RMS distance of the points to the plane [m]
  bool valid = false;
};
PlaneFit fitPlane(const Eigen::Vector3f* points, int count, double max_distance);
inline PlaneFit fitPlane(const std::vector<Eigen::Vector3f>& points, double max_distance) {
  return fitPlane(points.data(), static_cast<int>(points.size()), max_distance);
}

/// The plane of the largest face among the points, for neighbourhoods that
/// may span two surfaces (a stair's tread and riser, a slab's underside and a
/// flight's soffit), where one least-squares plane through all of them is a
/// false, slanted plane that can still pass `max_distance`. Points whose
/// least-squares plane is within half of `max_distance` of each of them are
/// one surface: that plane, all points. Otherwise, of the planes through
/// three of the points (with `query`: only those within `max_distance` of
/// it, so that the face is the query's own and not the next tread's), the
/// one with the most points within half of `max_distance` (ties: the smaller
/// sum of their squared distances) is refit by PCA on those, its points
/// within half of `max_distance` are taken again and refit. `valid` when at
/// least `min_inliers` points remain and fitPlane accepts them; `inliers`
/// gets their mask (bit i: point i).
PlaneFit fitPlaneLargestFace(const Eigen::Vector3f* points, int count, double max_distance,
                             int min_inliers, std::uint32_t* inliers = nullptr,
                             const Eigen::Vector3f* query = nullptr);

/// Line through `point` along unit `direction` fitted by PCA; `valid` only when
/// the points are clearly elongated (largest eigenvalue > `min_ratio` x the second).
struct LineFit {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  double thickness = 0.0;  ///< RMS distance of the points to the line [m]
  bool valid = false;
};
LineFit fitLine(const Eigen::Vector3f* points, int count, double min_ratio);
inline LineFit fitLine(const std::vector<Eigen::Vector3f>& points, double min_ratio) {
  return fitLine(points.data(), static_cast<int>(points.size()), min_ratio);
}

}  // namespace storey
