#pragma once
/// Small pieces the views share (internal to render/).
#include <string>
#include <vector>

#include "render/views.h"

namespace storey::render {

/// Splits a trajectory into polylines of consecutive poses that pass `keep`.
template <typename Keep>
std::vector<std::vector<Eigen::Vector3d>> trajectoryRuns(const Trajectory& trajectory, Keep keep) {
  std::vector<std::vector<Eigen::Vector3d>> runs;
  std::vector<Eigen::Vector3d> current;
  for (const StampedPose& p : trajectory) {
    if (keep(p.pose.translation())) {
      current.push_back(p.pose.translation());
    } else if (!current.empty()) {
      if (current.size() >= 2) runs.push_back(std::move(current));
      current.clear();
    }
  }
  if (current.size() >= 2) runs.push_back(std::move(current));
  return runs;
}

std::vector<Eigen::Vector3d> polyline(const Trajectory& trajectory);

/// "12.3", "-0.61" etc.
std::string fixed(double value, int decimals);
/// Thousands separated with a thin space: "1 523 311".
std::string count(std::size_t n);

/// z range [lo, hi) of storey `index` for display (ceiling cut applied);
/// the whole map when there are no storeys.
void storeyZRange(const ViewContext& context, int storey_index, double& lo, double& hi);

/// Legend lines shared by the views: run name, points drawn.
std::string mapLine(const ViewContext& context, std::size_t drawn);

/// Horizontal viewing direction rotated `degrees` from the building's x axis.
Eigen::Vector3d horizontal(const ViewContext& context, double degrees);
/// Oblique direction looking down at `elevation_deg` along `horizontal_direction`.
Eigen::Vector3d oblique(const Eigen::Vector3d& horizontal_direction, double elevation_deg);

}  // namespace storey::render
