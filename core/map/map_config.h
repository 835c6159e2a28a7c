#pragma once
/// Parameters of map assembly (core/map): how the keyframe scans become the
/// registered, voxel-downsampled map. Defaults here; units beside each field.

namespace storey {

struct MapConfig {
  double voxel_size = 0.02;  ///< map resolution: one point (the centroid) per voxel edge [m, > 0]
  double max_range = 40.0;   ///< keyframe points farther from the sensor are left out [m, > 0]
  bool spill_to_disk = true;  ///< keep the keyframe scans in an anonymous temporary file, not RAM
};

}  // namespace storey
