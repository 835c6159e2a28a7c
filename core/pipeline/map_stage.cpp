#include "pipeline/map_stage.h"

#include <cstdio>

#include "common/log.h"
#include "common/memory.h"
#include "common/stopwatch.h"
#include "export/map_export.h"

namespace storey {

MapStage buildMapStage(MapScanSelector& map_scans, const SlamResult& slam,
                       const StoreysConfig& storeys_config, const std::string& out_dir,
                       const ProgressFn& progress) {
  MapStage stage;
  const MapBuilder& builder = *map_scans.builder();
  Stopwatch watch;
  std::vector<Pose> T_world_lidar_per_map_scan;
  for (std::size_t s : map_scans.trajectoryIndices())
    T_world_lidar_per_map_scan.push_back(slam.trajectory[s].pose);
  MapCloud map = builder.build(T_world_lidar_per_map_scan, progress);
  stage.seconds_build = watch.seconds();
  stage.peak_mib_after_build = peakResidentMiB();
  stage.build = builder.stats();
  stage.voxel_size = builder.config().voxel_size;
  const int export_threads = builder.config().export_threads;
  logInfo("map: " + std::to_string(map.size()) + " points from " +
          std::to_string(stage.build.scans) + " scans");
  map_scans.release();  // the stored scans are no longer needed

  watch = Stopwatch();
  if (storeys_config.enabled) {
    // The keyframes' positions orient the normals and locate the stairs
    // (MapCloud::keyframe labels index them).
    std::vector<Eigen::Vector3d> keyframe_positions;
    for (const StampedPose& k : slam.keyframes) keyframe_positions.push_back(k.pose.translation());
    stage.storeys = segmentStoreys(map, keyframe_positions, storeys_config, progress);
    if (stage.storeys.storeys.empty())
      logWarning("storeys: no floor slab of at least " +
                 std::to_string(storeys_config.min_floor_area) + " m^2 found; no storeys");
  } else {
    logInfo("storeys: segmentation switched off (storeys.enabled: false)");
  }
  stage.seconds_storeys = watch.seconds();
  stage.peak_mib_after_storeys = peakResidentMiB();
  for (const StoreyInfo& s : stage.storeys.storeys) {
    char line[160];
    std::snprintf(line, sizeof(line), "storey %d: floor %.3f m, footprint %.1f m^2, %zu points",
                  s.index, s.floor_elevation, s.footprint_area, s.points);
    logInfo(line);
  }

  watch = Stopwatch();
  stage.files =
      writeMapFiles(out_dir, map, stage.storeys, stage.voxel_size, progress, export_threads);
  stage.seconds_export = watch.seconds();
  stage.peak_mib_after_export = peakResidentMiB();
  stage.map = std::make_shared<const MapCloud>(std::move(map));
  return stage;
}

}  // namespace storey
