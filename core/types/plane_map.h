#pragma once
/// The global plane map of a run: every global SRP (landmark) in the world
/// frame with its observations in the observing keyframes' LiDAR frames. The
/// back end produces it, export/planes_json.h writes and reads it
/// (OUT/planes.json, docs/outputs.md), eval, render and the plugin use it.
/// Planes in Hesse normal form n . x = d (|n| = 1, d >= 0), metres.
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace storey {

/// One plane seen from one keyframe.
struct PlaneObservation {
  int keyframe = -1;           ///< index into the run's keyframes (keyframes.tum)
  std::optional<double> time;  ///< the keyframe's time [s] (absent in old files)
  Eigen::Vector3d normal_keyframe = Eigen::Vector3d::UnitZ();  ///< keyframe LiDAR frame
  double distance_keyframe = 0.0;                              ///< [m], keyframe LiDAR frame
  std::optional<Eigen::Vector3d> centroid_keyframe;            ///< of the inliers [m]
  std::vector<Eigen::Vector3d> hull_keyframe;  ///< convex outline of the inliers on the plane,
                                               ///< counter-clockwise seen from the normal [m]
  long points = 0;                             ///< inliers
  double fit_rms = 0.0;                        ///< RMS distance of the inliers from the plane [m]
  double residual_chi2 = 0.0;  ///< whitened squared residual after the final solve (3 dof)
  bool outlier = false;        ///< down-weighted by the robust loss (residual beyond the limit)
};

/// A global plane (landmark) with its observations.
struct GlobalPlane {
  int id = 0;
  Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();  ///< Hesse form, world frame
  double distance_world = 0.0;                              ///< [m]
  /// Unit vector from the plane towards the side it was seen from (world);
  /// absent in old files.
  std::optional<Eigen::Vector3d> facing_world;
  std::vector<PlaneObservation> observations;
};

struct PlaneMap {
  long keyframes = 0;  ///< keyframes of the run (observations index them)
  std::vector<GlobalPlane> planes;
};

}  // namespace storey
