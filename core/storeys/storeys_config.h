#pragma once
/// Parameters of storey segmentation (core/storeys). Lengths in metres,
/// areas in square metres; the two angles are in degrees, as in the YAML file
/// (converted to radians where they are used). Defaults suit ordinary
/// buildings (storeys >= 2 m apart, floors larger than a stair landing); none
/// is tuned to a particular building.
namespace storey {

struct StoreysConfig {
  bool enabled = true;            ///< split the map into storeys (off: one map, no storey files)
  double voxel_size = 0.08;       ///< the map is subsampled to this for plane detection [m, > 0]
  int normal_neighbours = 12;     ///< neighbours of the PCA normal and of region growing [>= 6]
  double plane_distance = 0.05;   ///< region growing: largest point-to-plane distance [m]
  double plane_angle_deg = 15.0;  ///< region growing: largest normal deviation [deg]
  double min_region_area = 0.5;   ///< smaller planar regions are ignored [m^2]
  double horizontal_angle_deg =
      10.0;  ///< a region within this of horizontal is a floor/ceiling candidate [deg]
  double slab_tolerance = 0.15;  ///< regions this close in elevation form one slab [m]
  double min_floor_area = 10.0;  ///< a floor slab has at least this much upward-facing area [m^2]
  double min_storey_height =
      2.0;  ///< floors closer than this are one storey (the stairs' kept, else the larger) [m]
  double floor_tolerance = 0.15;  ///< points down to this below a floor belong to its storey [m]
  double min_clear_height = 1.8;  ///< ceilings are searched from this above the floor [m]
  double max_clear_height = 8.0;  ///< ... up to this (or the next floor) [m]
  double stairs_cell_size = 0.5;  ///< grid cell of the stairwell mask [m, > 0]
  double stairs_min_rise =
      0.3;  ///< sensor this far above its usual height over the floor: on stairs [m]
  double stairs_trajectory_distance =
      2.5;                       ///< stair cells lie this close (xy) to a stair keyframe [m]
  double footprint_alpha = 1.0;  ///< alpha-shape radius of the floor footprint [m, > 0]

  /// Checks value ranges; throws storey::Error naming the key (under `storeys.`) at fault.
  void validate() const;
};

}  // namespace storey
