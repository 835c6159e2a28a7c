#include "sim/world.h"

#include <cmath>

namespace storey::sim {

World makeWorld(const BuildingSpec& spec) {
  Building building = generateBuilding(spec);
  // The world frame of the outputs (Storey's convention): the LiDAR starts at
  // the origin, and its x axis, projected on the level plane, points along +x
  // (unless it points straight up or down). The start pose is level (no gait
  // while standing), so this only needs the building-frame trajectory's start.
  const Trajectory in_building(building.route, spec.robot);
  const Pose T_building_lidar = in_building.frame(0.0, spec.sensors.T_body_lidar).T_world_frame;
  const Eigen::Vector3d lidar_x = T_building_lidar.rotation() * Eigen::Vector3d::UnitX();
  const double yaw = lidar_x.head<2>().norm() > 0.1 ? std::atan2(lidar_x.y(), lidar_x.x()) : 0.0;
  building.translate(-T_building_lidar.translation());
  if (yaw != 0.0) building.rotateZ(-yaw);
  Trajectory trajectory(building.route, spec.robot);
  return World{std::move(building), std::move(trajectory)};
}

}  // namespace storey::sim
