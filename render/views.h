#pragma once
/// The images, each built as a Figure from a run's files (no VTK here).
/// docs/renders.md describes what each shows.
#include <optional>
#include <string>
#include <vector>

#include "config/render_config.h"
#include "render/figure.h"
#include "render/run_data.h"
#include "render/srp_patches.h"

namespace storey::render {

/// What every view shares: the run, the options, the building's axes and
/// the SRP patches with the map points on them.
struct ViewContext {
  const RunData* run = nullptr;
  RenderConfig config;
  std::string run_name;       ///< shown in subtitles
  double building_yaw = 0.0;  ///< main wall direction in the world [rad]
  Eigen::Vector3d axis_x = Eigen::Vector3d::UnitX(), axis_y = Eigen::Vector3d::UnitY();
  PatchSet patches;
  std::vector<int> srp_of_point;  ///< per map point: SRP id or -1
};

ViewContext makeViewContext(const RunData& run, const RenderConfig& config);

/// Main horizontal direction of the walls (vertical SRPs, weighted by their
/// observations), modulo 90 degrees; 0 without walls.
double buildingYaw(const std::vector<GlobalPlane>& planes);

/// "floor", "ceiling", "wall" or "slanted", from the plane's normal and seen side.
std::string planeKind(const Eigen::Vector3d& normal, const Eigen::Vector3d& facing);

Figure elevationFigure(const ViewContext& context, bool side);

struct NamedFigure {
  std::string file;  ///< e.g. "storey_00_top.png"
  Figure figure;
};
/// One top view per storey (the whole map when the run found no storey).
std::vector<NamedFigure> storeyTopFigures(const ViewContext& context);

Figure srpMapFigure(const ViewContext& context);

/// Keyframe with the most SRP observations (the first of equals); -1 without any.
int keyframeWithMostSrps(const ViewContext& context);
/// Throws storey::Error when `keyframe` is not in keyframes.tum.
Figure srpKeyframeFigure(const ViewContext& context, int keyframe);

struct NamedTrajectory {
  std::string name;
  Trajectory trajectory;
};
struct TrajectoryComparison {
  NamedTrajectory truth;
  std::vector<NamedTrajectory> estimates;  ///< the run's first, then --compare runs
  std::vector<std::string> legend_notes;   ///< ATE etc., one per estimate
  std::string alignment;                   ///< how the truth was put in the run's frame
};
/// Puts the truth into the run's world frame (no alignment when both start
/// at the same pose, otherwise yaw + translation) and computes the ATE of each estimate.
TrajectoryComparison compareTrajectories(const Trajectory& truth, const std::string& truth_name,
                                         const std::vector<NamedTrajectory>& estimates);
Figure trajectoryFigure(const ViewContext& context, const TrajectoryComparison& comparison,
                        bool top);

}  // namespace storey::render
