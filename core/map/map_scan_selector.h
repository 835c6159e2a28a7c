#pragma once
/// Which scans of the log make the map (MapConfig): every keyframe of the
/// back end, and in between a scan whenever the LiDAR moved farther than
/// MapConfig::scan_spacing or turned more than MapConfig::scan_angle_deg
/// since the last map scan. The last scan of the log is the last keyframe,
/// so it is in the map too. Selected scans go into a MapBuilder (on disk by
/// default); each remembers its index in the log's trajectory (to be placed
/// at its final pose) and the keyframe whose part of the walk it belongs to
/// (MapCloud::keyframe of its points). With the map off it selects nothing.
#include <cstddef>
#include <memory>
#include <vector>

#include "map/map_builder.h"
#include "map/map_config.h"
#include "types/pose.h"
#include "types/scan.h"

namespace storey {

class MapScanSelector {
 public:
  explicit MapScanSelector(const MapConfig& config);

  /// The next scan of the log (scan index = its place in the trajectory),
  /// with the back end's pose and keyframe decision.
  void addScan(const Scan& deskewed, const Pose& T_world_lidar, bool keyframe);
  /// End of the log: the last scan (the one given to the last addScan,
  /// `last_deskewed`) becomes the last keyframe and enters the map if it is
  /// not there yet.
  void finish(const Scan& last_deskewed);

  bool enabled() const { return builder_ != nullptr; }
  /// The scans kept (null when the map is off).
  const MapBuilder* builder() const { return builder_.get(); }
  /// Per map scan (MapBuilder index): its index in the log's trajectory.
  const std::vector<std::size_t>& trajectoryIndices() const { return trajectory_index_; }
  /// Frees the stored scans (after the map was built).
  void release();

 private:
  void add(const Scan& deskewed, const Pose& T_world_lidar, std::size_t scan_index);

  MapConfig config_;
  std::unique_ptr<MapBuilder> builder_;
  std::vector<std::size_t> trajectory_index_;
  std::size_t scans_ = 0;  ///< scans seen
  int keyframes_ = 0;      ///< keyframes seen
  Pose T_world_last_map_scan_;
  bool last_in_map_ = false;
  Pose T_world_last_scan_;
};

}  // namespace storey
