#pragma once
/// planes.json (format "storey planes, version 1", docs/outputs.md): the one
/// writer and the one reader of the global plane map (types/plane_map.h).
/// eval, render and the CloudCompare plugin all read it through here.
#include <string>

#include "types/plane_map.h"

namespace storey {

/// planes.json text (no trailing newline).
std::string planesJsonText(const PlaneMap& planes);
/// Writes planesJsonText() and a newline atomically.
void writePlanesJson(const std::string& path, const PlaneMap& planes);

/// Parses planes.json text; `source` names it in errors. Required: a "planes"
/// array; per plane "normal" and "distance" ("id" defaults to its index);
/// per observation "keyframe", "normal" and "distance". Other fields are
/// optional (older files). Throws storey::Error "<source>: <where>: <what>".
PlaneMap parsePlanesJson(const std::string& json_text, const std::string& source);
/// Reads a planes.json file (storey::Error when it cannot be opened or parsed).
PlaneMap readPlanesJson(const std::string& path);

}  // namespace storey
