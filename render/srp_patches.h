#pragma once
/// SRP observations placed in the world: each observation's convex hull
/// (planes.json, keyframe LiDAR frame) moved by its keyframe pose
/// T_world_lidar, and the map points that lie on a patch (within a distance
/// of its plane and inside its hull). When planes.json has no hulls (older
/// runs) a patch is estimated: the convex hull of the map points near the
/// observed plane within `fallback_radius` of the keyframe.
#include <Eigen/Core>
#include <vector>

#include "render/run_data.h"

namespace storey::render {

struct WorldPatch {
  int plane_id = 0;     ///< global SRP id
  int plane_index = 0;  ///< index into RunData::planes
  int keyframe = 0;
  int observation = 0;                                ///< index into the plane's observations
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< world plane of the observation
  double distance = 0.0;
  Eigen::Vector3d facing = Eigen::Vector3d::UnitZ();  ///< towards the side it was seen from
  std::vector<Eigen::Vector3d> hull;                  ///< world, convex, in order
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  bool estimated = false;  ///< hull from map points (planes.json had none)
};

struct PatchSet {
  std::vector<WorldPatch> patches;
  std::size_t estimated = 0;  ///< patches without a hull in planes.json
  std::size_t skipped = 0;    ///< observations with no usable keyframe or hull
};

PatchSet worldPatches(const RunData& run, double point_distance, double fallback_radius);

/// For each map point: the SRP id of the first patch it lies on, or -1.
/// Only patches whose index is in `use` (all when empty) count.
std::vector<int> srpOfPoints(const MapSample& map, const std::vector<WorldPatch>& patches,
                             double point_distance, const std::vector<int>& use = {});

/// Orthonormal basis (u, v) of the plane with normal n.
void planeBasis(const Eigen::Vector3d& n, Eigen::Vector3d& u, Eigen::Vector3d& v);

}  // namespace storey::render
