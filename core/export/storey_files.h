#pragma once
/// One file (or two) per storey of a labelled map: `DIR/storey_NN.las` and/or
/// `DIR/storey_NN.ply` (NN = storey index, two digits) with the core's
/// writers (point_cloud_writers.h, formats in docs/outputs.md). The map
/// stage (map_export.h) and the plugin's "Export storeys" write through here.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "map/map_cloud.h"

namespace storey {

/// Which files writeStoreyFiles() writes per storey.
struct StoreyFileFormats {
  bool las = true;   ///< storey_NN.las (LAS 1.4)
  bool ply = false;  ///< storey_NN.ply (binary PLY)
};

/// Storey indices present in `map` (sorted; kNoStorey left out).
std::vector<int> storeyIndices(const MapCloud& map);
/// Indices of the points of `map` labelled with `storey`, in order.
std::vector<std::uint32_t> pointsOfStorey(const MapCloud& map, int storey);

/// "storey_NN" for storey NN.
std::string storeyStem(int storey);

/// Writes the files of the listed storeys (each gets its files, even an
/// empty one) into `dir` (created when missing), in the order given, LAS
/// before PLY; `on_file` (optional) is called with each path once written.
/// Returns the paths written. Throws storey::Error when the folder cannot be
/// created or a write fails.
std::vector<std::string> writeStoreyFiles(
    const MapCloud& map, const std::vector<int>& storeys, const std::string& dir,
    const StoreyFileFormats& formats, const std::function<void(const std::string&)>& on_file = {});

/// Writes the files of every storey of `map` into `dir` (created when
/// missing), storeys in index order, LAS before PLY; returns the paths
/// written. Throws storey::Error when the map has no storey labels (nothing
/// is written then), the folder cannot be created or a write fails.
std::vector<std::string> writeStoreyFiles(const MapCloud& map, const std::string& dir,
                                          const StoreyFileFormats& formats);

}  // namespace storey
