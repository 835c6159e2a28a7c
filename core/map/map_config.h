#pragma once
/// Parameters of map assembly (core/map): how the keyframe scans become the
/// registered, voxel-downsampled map. Defaults here; units beside each field.

namespace storey {

struct MapConfig {
  bool enabled = true;  ///< build and export the registered map (and the storeys)
  /// Scans of the map: every graph keyframe, and in between a scan whenever
  /// the LiDAR moved farther than scan_spacing or turned (any axis) more than
  /// scan_angle_deg since the last map scan (denser than the graph's keyframes,
  /// so floors and walls are covered between the rings of single scans).
  double scan_spacing = 0.5;     ///< [m, > 0]
  double scan_angle_deg = 10.0;  ///< [deg, > 0]
  double voxel_size = 0.02;   ///< map resolution: one point (the centroid) per voxel edge [m, > 0]
  double max_range = 40.0;    ///< keyframe points farther from the sensor are left out [m, > 0]
  bool spill_to_disk = true;  ///< keep the keyframe scans in an anonymous temporary file, not RAM
  /// Threads of build(): the map's voxels in this many parts of the key space,
  /// merged at once (the same cloud with any number) [1, 64].
  int build_threads = 2;
  int export_threads = 2;  ///< map files written at once (each by one thread; same bytes) [1, 64]

  /// Checks value ranges; throws storey::Error naming the key (under `map.`) at fault.
  void validate() const;
};

}  // namespace storey
