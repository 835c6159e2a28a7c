#pragma once
/// The registered map: one point per occupied voxel, in the world frame, with
/// per-point attributes kept in parallel arrays (structure of arrays, so a
/// writer or a face can take the columns it needs).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace storey {

/// Bits of MapCloud::flags.
enum MapPointFlag : std::uint8_t {
  kMapPointStairs = 1u << 0,  ///< in a stairwell between two floors (storey = the one below)
  kMapPointFloor = 1u << 1,   ///< on a detected floor slab
};

/// Storey index of a point that no storey was assigned to.
inline constexpr std::int16_t kNoStorey = -1;

struct MapCloud {
  std::vector<Eigen::Vector3f> positions;  ///< world frame (z up) [m]
  std::vector<float> intensity;            ///< mean return intensity of the voxel [sensor units]
  std::vector<double> time;           ///< absolute time of the first return in the voxel [s]
  std::vector<std::int32_t> keyframe;  ///< keyframe that first observed the voxel
  std::vector<std::int16_t> storey;    ///< storey index (0 = lowest), kNoStorey before labelling
  std::vector<std::uint8_t> flags;     ///< MapPointFlag bits

  std::size_t size() const { return positions.size(); }
  bool empty() const { return positions.empty(); }
  void reserve(std::size_t n);
  void clear();
  /// Appends point `i` of `other`.
  void pushFrom(const MapCloud& other, std::size_t i);
  /// Axis-aligned bounds; (0, 0, 0) both for an empty cloud [m].
  void bounds(Eigen::Vector3d& min, Eigen::Vector3d& max) const;
};

}  // namespace storey
