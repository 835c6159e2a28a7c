#include "sim/world.h"

namespace storey::sim {

World makeWorld(const BuildingSpec& spec) {
  Building building = generateBuilding(spec);
  // Shift so the LiDAR starts at the origin. The start pose is level (no gait
  // while standing), so this only needs the building-frame trajectory's start.
  const Trajectory in_building(building.route, spec.robot);
  const Eigen::Vector3d lidar_start =
      in_building.frame(0.0, spec.sensors.T_body_lidar).T_world_frame.translation();
  building.translate(-lidar_start);
  Trajectory trajectory(building.route, spec.robot);
  return World{std::move(building), std::move(trajectory)};
}

}  // namespace storey::sim
