#pragma once
/// A hand-made run folder for the render tests: one room (8 x 6 m, 2.6 m
/// high) scanned from two keyframes, with planes.json carrying per
/// observation `centroid` and `hull` in the keyframe's LiDAR frame, map.ply
/// in our layout, storeys.json, trajectory.tum, keyframes.tum, report.json.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace storey::test {

struct MapPoint {
  Eigen::Vector3f p;
  int keyframe = 0;
  int storey = 0;
  bool stairs = false;
};

/// Writes map.ply in the layout of docs/outputs.md.
void writeMapPly(const std::string& path, const std::vector<MapPoint>& points);

/// Writes the room run into `dir`; returns the number of SRPs (planes) in planes.json.
int writeRoomRun(const std::string& dir);

}  // namespace storey::test
