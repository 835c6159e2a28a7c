#include "storeys/storeys_config.h"

#include <string>

#include "common/error.h"

namespace storey {

void StoreysConfig::validate() const {
  const StoreysConfig& c = *this;
  auto positive = [](double v, const char* key) {
    if (!(v > 0.0)) throw Error(std::string("key 'storeys.") + key + "' must be positive");
  };
  positive(c.voxel_size, "voxel_size");
  positive(c.plane_distance, "plane_distance");
  positive(c.min_region_area, "min_region_area");
  positive(c.slab_tolerance, "slab_tolerance");
  positive(c.min_floor_area, "min_floor_area");
  positive(c.min_storey_height, "min_storey_height");
  positive(c.floor_tolerance, "floor_tolerance");
  positive(c.min_clear_height, "min_clear_height");
  positive(c.stairs_cell_size, "stairs_cell_size");
  positive(c.stairs_min_rise, "stairs_min_rise");
  positive(c.stairs_trajectory_distance, "stairs_trajectory_distance");
  positive(c.footprint_alpha, "footprint_alpha");
  if (c.normal_neighbours < 6) throw Error("key 'storeys.normal_neighbours' must be >= 6");
  if (!(c.plane_angle_deg > 0.0 && c.plane_angle_deg <= 90.0))
    throw Error("key 'storeys.plane_angle_deg' must be in (0, 90]");
  if (!(c.horizontal_angle_deg > 0.0 && c.horizontal_angle_deg < 90.0))
    throw Error("key 'storeys.horizontal_angle_deg' must be in (0, 90)");
  if (!(c.max_clear_height > c.min_clear_height))
    throw Error("key 'storeys.max_clear_height' must be larger than 'storeys.min_clear_height'");
  if (!(c.floor_tolerance < c.min_storey_height))
    throw Error("key 'storeys.floor_tolerance' must be below 'storeys.min_storey_height'");
}

}  // namespace storey
