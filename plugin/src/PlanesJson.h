#pragma once
/// The global SRPs of a run (PipelineResult::planes_json, format in
/// docs/outputs.md) as plain structs, and the rectangle that shows each one:
/// the bounding rectangle, in the plane, of its observations' convex hulls
/// placed in the world by their keyframe poses. No Qt, no CloudCompare.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "trajectory/tum.h"

namespace storey::plugin {

struct PlaneObservation {
  int keyframe = -1;                           ///< index into the run's keyframes
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< keyframe LiDAR frame
  double distance = 0.0;                       ///< [m], keyframe LiDAR frame
  long points = 0;                             ///< inliers
  double fit_rms = 0.0;                        ///< [m]
  double residual_chi2 = 0.0;
  bool outlier = false;
  std::optional<Eigen::Vector3d> centroid;     ///< of the inliers, keyframe LiDAR frame [m]
  std::vector<Eigen::Vector3d> hull;           ///< convex hull of the inliers, keyframe LiDAR frame [m]
};

struct GlobalPlane {
  int id = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< world, Hesse form n . x = d
  double distance = 0.0;                              ///< [m]
  /// From the plane towards the side it was seen from (world); absent in old files.
  std::optional<Eigen::Vector3d> facing;
  std::vector<PlaneObservation> observations;
};

/// "floor" (horizontal, seen from above), "ceiling" (horizontal, seen from
/// below), "wall" (vertical), or "plane"; horizontal/vertical within 20 deg.
/// Without `facing` a horizontal plane is "floor" when the observing sensors
/// were above it, else "ceiling".
std::string planeKind(const GlobalPlane& plane, const Trajectory& keyframes);

/// Parses planes.json text. Throws storey::Error when it is not that format.
std::vector<GlobalPlane> parsePlanesJson(const std::string& json_text);

/// A rectangle on a plane, world frame.
struct PlanePatch {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< on the plane [m]
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();      ///< width direction (horizontal for walls)
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();      ///< height direction, v = n x u
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double width = 0.0;   ///< along u [m]
  double height = 0.0;  ///< along v [m]
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
