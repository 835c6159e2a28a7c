#pragma once
/// The whole pipeline on one log, as the paper's method section reads:
/// read -> odometry (IMU initialisation, deskew, features, joint
/// optimisation) -> back end (SRP or odometry only) -> map, storeys, exports.
/// The CLI and the CloudCompare plugin both call this. The stages and the
/// order of the layers: docs/architecture.md.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/progress.h"
#include "config/config.h"
#include "map/map_cloud.h"
#include "storeys/storey_segmentation.h"
#include "trajectory/tum.h"
#include "types/plane_map.h"

namespace storey {

struct PipelineResult {
  Trajectory odometry;    ///< front-end pose of the LiDAR per scan (scan header stamps)
  Trajectory trajectory;  ///< final pose per scan (= odometry while the back end is off)
  Trajectory keyframes;   ///< map keyframes at their final poses (index = MapCloud::keyframe)
  std::optional<PlaneMap> planes;  ///< global SRPs (OUT/planes.json); absent with the back end off
  /// The registered map, every point labelled with its storey (kNoStorey when
  /// storeys are off); null when config.map.enabled is false.
  std::shared_ptr<const MapCloud> map;
  std::vector<StoreyInfo> storeys;  ///< bottom up; empty when storeys are off or none found
  std::vector<std::string> files;   ///< files written, relative to out_dir
  std::string report_json;          ///< the run report (also written to OUT/report.json)
};

/// Runs the pipeline on `log_path` and writes into `out_dir` (created when
/// missing): odometry.tum, trajectory.tum, trajectory_kitti*.txt, keyframes.tum,
/// planes.json (back end on), map.las/ply/pcd, storeys/, storeys.json (map on),
/// report.json, report.md and report.html (names and formats in docs/outputs.md).
/// Every file is written atomically and only after the whole log was
/// processed, so a failed run leaves no output behind. `progress` may return
/// false to cancel (storey::Cancelled is thrown); `log_time` gets the log time
/// read so far with each progress report of the odometry stage. The warnings
/// logged during the run go into the report. Throws storey::Error on bad input.
PipelineResult runPipeline(const std::string& log_path, const Config& config,
                           const std::string& out_dir, const ProgressFn& progress = nullptr,
                           const LogTimeFn& log_time = nullptr);

}  // namespace storey
