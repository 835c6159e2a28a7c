#pragma once
/// The map stage's entry point for the pipeline: build the registered map
/// from the keyframe scans at their final poses, segment it into storeys and
/// write every map output into OUT (names as in DESIGN.md "Outputs of storey
/// run"; formats in docs/outputs.md):
///
///   map.las map.ply map.pcd              whole map
///   storeys/storey_NN.las storey_NN.ply  one per storey (NN = index, two digits)
///   storeys.json                         storey table
///
/// Each file is written atomically; nothing is written when building or
/// segmenting fails. The run report (report.json/report.md) and the
/// trajectories stay with the pipeline: addMapToReport(), writeReportMarkdown()
/// and writeKitti() are its helpers.
#include <memory>
#include <string>
#include <vector>

#include "common/progress.h"
#include "map/map_builder.h"
#include "storeys/storey_segmentation.h"

namespace storey {

struct MapOutputs {
  std::shared_ptr<MapCloud> map;    ///< the built map, labelled with storeys
  std::vector<std::string> files;   ///< written, relative to out_dir
  std::vector<StoreyInfo> storeys;  ///< the storey table, bottom up
  StoreySegmentationStats segmentation;
  MapBuildStats build;
  std::size_t map_points = 0;
  double map_voxel_size = 0.0;  ///< [m]
  double seconds_build = 0.0, seconds_storeys = 0.0, seconds_export = 0.0;  ///< wall time [s]
};

/// build() + segmentStoreys() (skipped when storeys_config.enabled is false:
/// every point keeps kNoStorey and storeys.json lists none) + exportMap().
/// `T_world_lidar_per_scan` is indexed by the scan indices given to
/// MapBuilder::addKeyframeScan; `sensor_position_per_label` (world position of
/// the LiDAR per MapCloud::keyframe label: the keyframes) orients the normals
/// and locates the stairs. Throws storey::Error.
MapOutputs buildAndExportMap(const MapBuilder& builder,
                             const std::vector<Pose>& T_world_lidar_per_scan,
                             const std::vector<Eigen::Vector3d>& sensor_position_per_label,
                             const StoreysConfig& storeys_config, const std::string& out_dir,
                             const ProgressFn& progress = {});

/// Writes the files listed above for an already built and labelled map;
/// stale storeys/storey_NN.* files of a previous run with more storeys are removed.
/// Returns the written files (relative to out_dir).
std::vector<std::string> exportMap(const MapCloud& map, const StoreySegmentation& storeys,
                                   double map_voxel_size, const std::string& out_dir,
                                   const ProgressFn& progress = {});

/// storeys.json text (format in docs/outputs.md; core/eval reads it).
std::string storeysJson(const std::vector<StoreyInfo>& storeys, double map_voxel_size);

/// The run report (report.json text) with two sections added: "map" (points,
/// files, build and segmentation counts, timings) and "storeys" (the table).
std::string addMapToReport(const std::string& report_json, const MapOutputs& outputs);

}  // namespace storey
