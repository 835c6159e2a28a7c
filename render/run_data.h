#pragma once
/// What the renders read from a finished run's folder: map.ply (a uniform
/// subsample of at most max_display_points), trajectory.tum, keyframes.tum,
/// planes.json, storeys.json. Missing optional files leave their part empty
/// and add a note; a malformed file is a storey::Error naming it.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "map/map_cloud.h"
#include "trajectory/tum.h"
#include "types/plane_map.h"

namespace storey::render {

/// Map points kept for display, with the per-point attributes of map.ply.
struct MapSample {
  std::vector<Eigen::Vector3f> positions;  ///< world frame [m]
  std::vector<std::int32_t> keyframe;      ///< -1 when the file has no `keyframe`
  std::vector<std::int16_t> storey;        ///< -1 = none (or no `storey` in the file)
  std::vector<std::uint8_t> stairs;        ///< 0 / 1
  std::size_t file_points = 0;             ///< vertices in the file
  std::size_t size() const { return positions.size(); }
};

/// Reads our binary PLY layout (docs/outputs.md): binary_little_endian,
/// element vertex first; x y z required (float or double), keyframe, storey,
/// stairs used when present, other properties skipped. Keeps every point
/// when the file has at most max_points, otherwise a uniform deterministic
/// subsample of about max_points (each vertex by a hash of its index).
MapSample readMapSample(const std::string& path, std::size_t max_points);

/// The same sample taken from the map in memory (what map.ply holds, point
/// for point): `storey run` hands it to its renders, which then need not read
/// the file back.
MapSample sampleMap(const MapCloud& map, std::size_t max_points);

/// The uniform subsample's rule, shared by both: the vertex of index `index`
/// of `points` is kept when its hash is at most the threshold.
class DisplaySubsample {
 public:
  DisplaySubsample(std::size_t points, std::size_t max_points);
  bool keeps(std::size_t index) const;
  std::size_t reserve() const { return reserve_; }

 private:
  bool all_ = true;
  std::uint64_t threshold_ = ~0ull;
  std::size_t reserve_ = 0;
};

/// The side a plane was seen from (world): its `facing`, or -normal in files without it.
Eigen::Vector3d facingOf(const GlobalPlane& plane);

struct StoreyEntry {
  int index = 0;
  double floor = 0.0;             ///< floor elevation [m]
  std::optional<double> ceiling;  ///< [m]
  std::optional<double> height;   ///< floor to next floor [m]
  double area = 0.0;              ///< [m^2]
  std::size_t points = 0;
  std::vector<Eigen::Vector2d> footprint;  ///< world x y
};

std::vector<StoreyEntry> readStoreysJson(const std::string& path);

struct RunData {
  std::string dir;
  MapSample map;
  Trajectory trajectory;            ///< trajectory.tum (required)
  Trajectory keyframes;             ///< keyframes.tum (empty without the back end)
  std::vector<GlobalPlane> planes;  ///< planes.json (export/planes_json.h)
  std::vector<StoreyEntry> storeys;
  std::vector<std::string> notes;  ///< files missing and what is left out
};

/// Reads the run's files; the map sample is `map_sample` when given (then
/// map.ply is not read), else read from map.ply.
RunData loadRun(const std::string& dir, std::size_t max_points,
                const MapSample* map_sample = nullptr);

/// Storey of elevation z by the rule of docs/outputs.md ([floor - tolerance,
/// next floor - tolerance)); -1 without storeys.
int storeyOfElevation(const std::vector<StoreyEntry>& storeys, double z, double tolerance = 0.15);

}  // namespace storey::render
