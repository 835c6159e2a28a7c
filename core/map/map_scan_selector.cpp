#include "map/map_scan_selector.h"

#include <Eigen/Geometry>
#include <cmath>
#include <utility>

namespace storey {

MapScanSelector::MapScanSelector(const MapConfig& config) : config_(config) {
  if (config.enabled) builder_ = std::make_unique<MapBuilder>(config);
}

void MapScanSelector::add(const Scan& deskewed, const Pose& T_world_lidar, std::size_t scan_index) {
  builder_->addScan(static_cast<int>(trajectory_index_.size()), deskewed, keyframes_ - 1);
  trajectory_index_.push_back(scan_index);
  T_world_last_map_scan_ = T_world_lidar;
}

void MapScanSelector::addScan(const Scan& deskewed, const Pose& T_world_lidar, bool keyframe) {
  const std::size_t scan_index = scans_++;
  if (keyframe) ++keyframes_;
  if (!builder_) return;
  const Pose step = T_world_last_map_scan_.inverse() * T_world_lidar;
  last_in_map_ = keyframe || step.translation().norm() > config_.scan_spacing ||
                 Eigen::AngleAxisd(step.rotation()).angle() > config_.scan_angle_deg * M_PI / 180.0;
  if (last_in_map_)
    add(deskewed, T_world_lidar, scan_index);
  else
    T_world_last_scan_ = T_world_lidar;
}

void MapScanSelector::finish(const Scan& last_deskewed) {
  if (!builder_ || scans_ == 0 || last_in_map_) return;
  ++keyframes_;  // the last scan is a keyframe (it was not one, or it would be in the map)
  add(last_deskewed, T_world_last_scan_, scans_ - 1);
  last_in_map_ = true;
}

void MapScanSelector::release() {
  builder_.reset();
}

}  // namespace storey
