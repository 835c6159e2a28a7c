#pragma once
/// The map stage: the selected scans at their final poses -> the registered
/// map (core/map) -> storeys (core/storeys) -> the map's files (core/export).
#include <memory>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "common/progress.h"
#include "map/map_builder.h"
#include "map/map_scan_selector.h"
#include "storeys/storey_segmentation.h"

namespace storey {

/// The map stage's results (the run report's "map" and "storeys" sections).
struct MapStage {
  std::shared_ptr<const MapCloud> map;  ///< every point labelled with its storey
  StoreySegmentation storeys;           ///< table and counts (empty when storeys are off)
  MapBuildStats build;
  double voxel_size = 0.0;                                                  ///< [m]
  double seconds_build = 0.0, seconds_storeys = 0.0, seconds_export = 0.0;  ///< wall time [s]
  /// The process's peak resident size at the end of each step [MiB] (-1: unknown).
  double peak_mib_after_build = -1.0, peak_mib_after_storeys = -1.0, peak_mib_after_export = -1.0;
  std::vector<std::string> files;  ///< written, relative to the output folder
};

/// Builds the map from the selected scans at their final poses
/// (slam.trajectory), segments it into storeys (unless storeys.enabled is
/// false), and writes its files into out_dir (export/map_export.h).
MapStage buildMapStage(MapScanSelector& map_scans, const SlamResult& slam,
                       const StoreysConfig& storeys, const std::string& out_dir,
                       const ProgressFn& progress);

}  // namespace storey
