#pragma once
/// The rectangle that shows a global SRP of a run (types/plane_map.h, read
/// and written by export/planes_json.h): the bounding rectangle, in the
/// plane, of its observations' convex hulls placed in the world by their
/// keyframe poses; and the plane's kind. No Qt, no CloudCompare.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "trajectory/tum.h"
#include "types/plane_map.h"

namespace storey::plugin {

/// "floor" (horizontal, seen from above), "ceiling" (horizontal, seen from
/// below), "wall" (vertical), or "plane"; horizontal/vertical within 20 deg.
/// Without `facing` a horizontal plane is "floor" when the observing sensors
/// were above it, else "ceiling".
std::string planeKind(const GlobalPlane& plane, const Trajectory& keyframes);

/// A rectangle on a plane, world frame.
struct PlanePatch {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< on the plane [m]
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();      ///< width direction (horizontal for walls)
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();      ///< height direction, v = n x u
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double width = 0.0;       ///< along u [m]
  double height = 0.0;      ///< along v [m]
  bool from_hulls = false;  ///< false: no hull in the file, fixed size around the observations
};

/// The patch of `plane`: bounds of the observation hulls (and centroids)
/// transformed by `keyframes[o.keyframe]`; without any, a `fallback_size`
/// square centred on the projection of the observing keyframes' positions.
PlanePatch planePatch(const GlobalPlane& plane, const Trajectory& keyframes,
                      double fallback_size = 3.0);

/// Distance-and-extent test used to label points with an SRP: |n.x - d| <=
/// tolerance and inside the patch grown by `margin`.
bool onPatch(const PlanePatch& patch, const Eigen::Vector3d& x, double tolerance, double margin);

}  // namespace storey::plugin
