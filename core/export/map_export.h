#pragma once
/// The map's files in OUT (names and formats in docs/outputs.md):
///
///   map.las map.ply map.pcd              whole map
///   storeys/storey_NN.las storey_NN.ply  one per storey (NN = index, two digits)
///   storeys.json                         storey table
///
/// Each file is written atomically. Writers only: the map is built by
/// core/map and segmented by core/storeys before.
#include <string>
#include <vector>

#include "common/progress.h"
#include "map/map_cloud.h"
#include "storeys/storey_segmentation.h"

namespace storey {

/// Writes the files listed above for a built and labelled map; stale
/// storeys/storey_NN.* files of a previous run with more storeys are removed.
/// Returns the written files (relative to out_dir). The files are written by
/// up to `threads` threads at once (each file by one; the same bytes).
std::vector<std::string> writeMapFiles(const std::string& out_dir, const MapCloud& map,
                                       const StoreySegmentation& storeys, double map_voxel_size,
                                       const ProgressFn& progress = {}, int threads = 1);

}  // namespace storey
