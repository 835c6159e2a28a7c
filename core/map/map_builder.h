#pragma once
/// Map assembly: the deskewed map scans (the keyframes and the scans between
/// them that map_scan_selector.h picks), placed at their final (optimised)
/// poses, merged and voxel-downsampled into one MapCloud.
///
/// Memory: each scan is downsampled in its own frame on arrival (same voxel
/// size as the map; points beyond MapConfig::max_range dropped) and stored
/// compactly (float position, intensity and time offset: 20 bytes a point),
/// by default in an anonymous temporary file (MapConfig::spill_to_disk), so
/// the RAM held while the log streams is a few bytes per keyframe. build()
/// streams the scans back in blocks into a hash grid of the map's voxels, in
/// MapConfig::build_threads parts of the key space merged at once (the same
/// cloud with any number; 32-byte accumulator + 8-byte key, in chunks that grow without
/// reallocation, + 16-32 bytes of open-addressing table per voxel, grown
/// with the map), then emits the MapCloud (31 bytes a point), freeing the
/// accumulators as it goes: peak memory is proportional to the map, not to
/// the log (building-a, 717 keyframes, 6.3 M map points: 260 MB of scans on
/// disk; peak RSS of odometry + map stage 634 MB, of which 175 MB before the
/// map stage, measured before the chunked accumulators; the one-hour
/// long-walk: docs/benchmarks.md).
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "common/progress.h"
#include "map/map_cloud.h"
#include "map/map_config.h"
#include "types/pose.h"
#include "types/scan.h"

namespace storey {

/// What the builder holds and what build() made of it.
struct MapBuildStats {
  std::int64_t scans = 0;                ///< scans added
  std::int64_t points_in = 0;            ///< points of the added scans
  std::int64_t points_beyond_range = 0;  ///< left out: farther than max_range
  std::int64_t points_non_finite = 0;    ///< left out: NaN/inf coordinates
  std::int64_t points_stored = 0;        ///< after the per-scan downsampling
  std::int64_t stored_bytes = 0;         ///< size of the scan store (file or RAM) [bytes]
};

class MapBuilder {
 public:
  /// Throws storey::Error when config.voxel_size or max_range is not positive,
  /// or when the temporary file cannot be created.
  explicit MapBuilder(const MapConfig& config = {});
  ~MapBuilder();
  MapBuilder(const MapBuilder&) = delete;
  MapBuilder& operator=(const MapBuilder&) = delete;

  /// Adds map scan number `map_scan` (>= 0; deskewed, LiDAR frame at the
  /// scan's reference time, per-point time relative to scan.stamp_ns). Each
  /// index may be added once; indices need not be contiguous. `keyframe`
  /// (default: `map_scan`) is what build() puts in MapCloud::keyframe for the
  /// points of this scan (the pipeline: the graph keyframe whose part of the
  /// walk the scan belongs to).
  void addScan(int map_scan, const Scan& deskewed_lidar, int keyframe = -1);

  /// Places every map scan at T_world_lidar_per_scan[map_scan] and merges
  /// them into voxels of MapConfig::voxel_size (position and intensity
  /// averaged; time and keyframe of the voxel's first return). Storeys are
  /// kNoStorey and flags 0 (the storey stage labels them). Throws
  /// storey::Error when a scan has no pose. Can be called again with other poses.
  MapCloud build(const std::vector<Pose>& T_world_lidar_per_scan,
                 const ProgressFn& progress = {}) const;

  const MapBuildStats& stats() const { return stats_; }
  const MapConfig& config() const { return config_; }

 private:
  struct StoredPoint {
    float x, y, z;  ///< LiDAR frame [m]
    float intensity;
    float dt;  ///< time relative to the scan stamp [s]
  };
  struct Entry {
    int map_scan = 0;
    int keyframe = 0;  ///< MapCloud::keyframe of its points
    std::int64_t stamp_ns = 0;
    std::uint64_t offset = 0;  ///< into the store, in points
    std::uint64_t count = 0;
  };
  void readPoints(const Entry& entry, std::vector<StoredPoint>& out) const;

  MapConfig config_;
  MapBuildStats stats_;
  std::vector<Entry> entries_;
  std::vector<int> entry_of_scan_;   ///< per map scan index; -1: not added
  std::FILE* file_ = nullptr;        ///< spill_to_disk
  std::vector<StoredPoint> memory_;  ///< !spill_to_disk
  std::uint64_t stored_points_ = 0;
};

}  // namespace storey
