#pragma once
/// Procedural multi-storey building from a spec: the triangle mesh, the true
/// storeys and the robot's route through it. Coordinates: x along the
/// corridor (west to east), y across it (north positive), z up; the route
/// starts on the ground floor heading +x.
#include <Eigen/Core>
#include <vector>

#include "sim/building_spec.h"
#include "sim/mesh.h"

namespace storey::sim {

struct StoreyTruth {
  int index = 0;           ///< 0 = ground floor
  double floor_z = 0.0;    ///< top of the floor slab [m]
  double ceiling_z = 0.0;  ///< underside of the slab above [m]
};

/// A corner of the robot's route (body centre). The robot walks straight
/// between corners; the trajectory planner rounds the corners.
struct RouteVertex {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  double speed = 0.0;  ///< speed limit on the segment that starts here [m/s]
};

struct Building {
  TriangleMesh mesh;
  std::vector<StoreyTruth> storeys;
  std::vector<RouteVertex> route;  ///< first and last vertex are the same point

  /// Moves everything (mesh, storeys, route) by `offset`.
  void translate(const Eigen::Vector3d& offset);
  /// Turns everything (mesh, route) about the world z axis by `yaw` [rad].
  void rotateZ(double yaw);
};

/// Generates the building and the route. Deterministic in spec (and spec.seed).
Building generateBuilding(const BuildingSpec& spec);

}  // namespace storey::sim
