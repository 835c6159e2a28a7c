#include "map/map_config.h"

#include <string>

#include "common/error.h"

namespace storey {

void MapConfig::validate() const {
  auto positive = [](double value, const char* key) {
    if (!(value > 0.0)) throw Error(std::string("key 'map.") + key + "' must be positive");
  };
  positive(scan_spacing, "scan_spacing");
  positive(scan_angle_deg, "scan_angle_deg");
  positive(voxel_size, "voxel_size");
  positive(max_range, "max_range");
  if (build_threads < 1 || build_threads > 64)
    throw Error("key 'map.build_threads' must be in [1, 64]");
  if (export_threads < 1 || export_threads > 64)
    throw Error("key 'map.export_threads' must be in [1, 64]");
}

}  // namespace storey
