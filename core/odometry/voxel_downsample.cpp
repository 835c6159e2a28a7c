#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "odometry/features.h"

namespace storey {
namespace {

struct VoxelAccumulator {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::uint32_t count = 0;
  std::uint32_t first_index = 0;  // keeps the output order deterministic
};

std::uint64_t voxelKey(const Eigen::Vector3f& p, double inverse_size) {
  // 21 bits per axis around the origin: +-1e6 voxels, plenty for a building.
  const auto cell = [&](float v) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v * inverse_size)) +
                                      (1 << 20)) &
           0x1FFFFF;
  };
  return (cell(p.x()) << 42) | (cell(p.y()) << 21) | cell(p.z());
}

}  // namespace

std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points,
                                             double voxel_size) {
  if (voxel_size <= 0.0) return points;
  const double inverse_size = 1.0 / voxel_size;
  std::unordered_map<std::uint64_t, VoxelAccumulator> voxels;
  voxels.reserve(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    auto [it, inserted] = voxels.try_emplace(voxelKey(points[i], inverse_size));
    if (inserted) it->second.first_index = i;
    it->second.sum += points[i].cast<double>();
    ++it->second.count;
  }
  std::vector<const VoxelAccumulator*> ordered;
  ordered.reserve(voxels.size());
  for (const auto& [key, voxel] : voxels) ordered.push_back(&voxel);
  std::sort(ordered.begin(), ordered.end(),
            [](const auto* a, const auto* b) { return a->first_index < b->first_index; });
  std::vector<Eigen::Vector3f> result;
  result.reserve(ordered.size());
  // The point nearest to each voxel's centroid represents it: a centroid of
  // points from two surfaces (a floor and a wall at their crease) would lie
  // on neither, a real point lies on its surface.
  std::unordered_map<std::uint64_t, std::pair<float, std::uint32_t>> nearest;
  nearest.reserve(voxels.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    const std::uint64_t key = voxelKey(points[i], inverse_size);
    const VoxelAccumulator& voxel = voxels.at(key);
    const float d2 = (points[i] - (voxel.sum / voxel.count).cast<float>()).squaredNorm();
    auto [it, inserted] = nearest.try_emplace(key, d2, i);
    if (!inserted && d2 < it->second.first) it->second = {d2, i};
  }
  for (const auto* voxel : ordered)
    result.push_back(points[nearest.at(voxelKey(points[voxel->first_index], inverse_size)).second]);
  return result;
}

}  // namespace storey
