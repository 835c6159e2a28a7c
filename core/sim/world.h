#pragma once
/// The simulated world: the building and the robot's trajectory, both in the
/// output world frame (z up, x = the LiDAR's initial heading projected on the
/// level plane, origin at the LiDAR's start position; Storey's world frame).
#include "sim/building.h"
#include "sim/building_spec.h"
#include "sim/trajectory.h"

namespace storey::sim {

struct World {
  Building building;
  Trajectory trajectory;
};

World makeWorld(const BuildingSpec& spec);

}  // namespace storey::sim
