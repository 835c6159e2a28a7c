#include <cmath>
#include <cstdint>

#include "odometry/features.h"
#include "types/voxel_hash.h"

namespace storey {
namespace {

std::uint64_t voxelKey(const Eigen::Vector3f& p, double inverse_size) {
  // 21 bits per axis around the origin: +-1e6 voxels, plenty for a building.
  const auto cell = [&](float v) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v * inverse_size)) +
                                      (1 << 20)) &
           0x1FFFFF;
  };
  return (cell(p.x()) << 42) | (cell(p.y()) << 21) | cell(p.z());
}

struct Voxel {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::uint32_t count = 0;
  std::uint32_t nearest = 0;  ///< the point nearest to the centroid so far
  float nearest_d2 = 0.0f;
  bool has_nearest = false;
};

}  // namespace

std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points,
                                             double voxel_size) {
  if (voxel_size <= 0.0) return points;
  const double inverse_size = 1.0 / voxel_size;
  // Voxels numbered in the order of their first point (the output's order).
  VoxelIndex index(points.size());
  std::vector<Voxel> voxels;
  std::vector<std::uint32_t> voxel_of(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    bool inserted = false;
    const std::uint32_t v = index.findOrInsert(voxelKey(points[i], inverse_size), inserted);
    if (inserted) voxels.emplace_back();
    voxel_of[i] = v;
    voxels[v].sum += points[i].cast<double>();
    ++voxels[v].count;
  }
  // The point nearest to each voxel's centroid represents it (the first of
  // equals): a centroid of points from two surfaces (a floor and a wall at
  // their crease) would lie on neither, a real point lies on its surface.
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    Voxel& voxel = voxels[voxel_of[i]];
    const float d2 = (points[i] - (voxel.sum / voxel.count).cast<float>()).squaredNorm();
    if (!voxel.has_nearest || d2 < voxel.nearest_d2) {
      voxel.nearest_d2 = d2;
      voxel.nearest = i;
      voxel.has_nearest = true;
    }
  }
  std::vector<Eigen::Vector3f> result;
  result.reserve(voxels.size());
  for (const Voxel& voxel : voxels) result.push_back(points[voxel.nearest]);
  return result;
}

}  // namespace storey
