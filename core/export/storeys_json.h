#pragma once
/// storeys.json (format "storey-storeys", version 1, docs/outputs.md): the one
/// writer and the one reader of the storey table. eval and render read it
/// through here.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "storeys/storey_segmentation.h"

namespace storey {

/// storeys.json text (with a trailing newline).
std::string storeysJson(const std::vector<StoreyInfo>& storeys, double map_voxel_size);
/// The storey table as storeys.json lists it (the run report shows it too).
nlohmann::json storeyTableJson(const std::vector<StoreyInfo>& storeys);

/// Parses storeys.json text (`source` names it in errors): an object with a
/// "storeys" array, or the array alone (files from other tools). Per storey
/// "index" (integer) and "floor_elevation" (number) are required, the other
/// fields optional ("area" is the footprint area). Throws storey::Error
/// "<source>: storeys[i]: <what>".
std::vector<StoreyInfo> parseStoreysJson(const std::string& json_text, const std::string& source);
/// Reads a storeys.json file (storey::Error when it cannot be opened or parsed).
std::vector<StoreyInfo> readStoreysJson(const std::string& path);

}  // namespace storey
