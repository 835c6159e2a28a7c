#pragma once
/// The simulated world: the building and the robot's trajectory, both in the
/// output world frame (z up, x = the LiDAR's initial heading (the IMU's when
/// the LiDAR looks straight up or down), origin at the LiDAR's start
/// position): the world frame of Storey's odometry. With the default mount
/// x is the robot's initial heading.
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
