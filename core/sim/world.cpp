#include "sim/world.h"

#include <cmath>

namespace storey::sim {

namespace {

/// Heading of a frame's x axis [rad]; false when it points (nearly) up or down.
bool headingOf(const Eigen::Matrix3d& R_world_frame, double& heading) {
  const Eigen::Vector3d x = R_world_frame.col(0);
  if (x.head<2>().norm() <= 0.1) return false;
  heading = std::atan2(x.y(), x.x());
  return true;
}

}  // namespace

World makeWorld(const BuildingSpec& spec) {
  Building building = generateBuilding(spec);
  // Shift so the LiDAR starts at the origin. The start pose is level (no gait
  // while standing), so this only needs the building-frame trajectory's start.
  const Trajectory in_building(building.route, spec.robot);
  const Pose lidar_start = in_building.frame(0.0, spec.sensors.T_body_lidar).T_world_frame;
  building.translate(-lidar_start.translation());
  // Turn so the LiDAR's initial heading is +x, as Storey's odometry sets its
  // world frame (the IMU's when the LiDAR looks straight up or down). With the
  // default mount that is the robot's heading: no turn, the same numbers.
  double heading = 0.0;
  if (!headingOf(lidar_start.rotationMatrix(), heading)) {
    headingOf(in_building.frame(0.0, spec.sensors.T_body_imu).T_world_frame.rotationMatrix(),
              heading);
  }
  if (heading != 0.0) {
    building.mesh.rotateAboutZ(-heading);
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(-heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (RouteVertex& v : building.route) v.p = R * v.p;
  }
  Trajectory trajectory(building.route, spec.robot);
  return World{std::move(building), std::move(trajectory)};
}

}  // namespace storey::sim
