#pragma once
/// The simulated world: the building and the robot's trajectory, both in the
/// output world frame (z up, x = initial heading, origin at the LiDAR's start
/// position).
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
