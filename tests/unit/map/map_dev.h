#pragma once
/// Development path until the lead integrates the map stage into
/// runPipeline: the same read -> odometry loop as core/pipeline, with a
/// simple keyframe rule (moved > 1 m or turned > 10 deg, as DESIGN.md) whose
/// deskewed scans go into a MapBuilder. Used by the end-to-end test and by
/// the storey_map_dev tool. Not part of storey_core.
#include <string>
#include <vector>

#include "config/config.h"
#include "map/map_builder.h"
#include "pipeline/run_report.h"
#include "trajectory/tum.h"

namespace storey::test {

struct DevRun {
  Trajectory trajectory;         ///< per scan (odometry)
  Trajectory keyframes;          ///< per keyframe
  std::vector<Pose> keyframe_poses;  ///< T_world_lidar by keyframe index
  std::string report_json;       ///< RunReportBuilder's report
};

DevRun runOdometryIntoMap(const std::string& log_path, const Config& config, MapBuilder& builder,
                          double keyframe_distance = 1.0, double keyframe_angle_deg = 10.0);

}  // namespace storey::test
