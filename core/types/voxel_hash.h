#pragma once
/// A compact open-addressing hash from a voxel's integer coordinates to a
/// dense index (0, 1, 2, ... in insertion order): 12 bytes a slot, grown
/// (doubled) at three-quarter load, so 16-32 bytes an entry. Used by map
/// assembly, the storey stage's subsampling and the odometry's feature
/// downsampling.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace storey {

/// Packs voxel coordinates (each within +-2^20 voxels) into 63 bits.
inline std::uint64_t packVoxel(std::int64_t i, std::int64_t j, std::int64_t k) {
  constexpr std::int64_t kBias = std::int64_t{1} << 20;
  constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
  return ((static_cast<std::uint64_t>(i + kBias) & kMask) << 42) |
         ((static_cast<std::uint64_t>(j + kBias) & kMask) << 21) |
         (static_cast<std::uint64_t>(k + kBias) & kMask);
}

/// Voxel of `p` for voxels of edge `1 / inverse_size` anchored at the origin.
inline std::uint64_t voxelKey(const Eigen::Vector3d& p, double inverse_size) {
  return packVoxel(static_cast<std::int64_t>(std::floor(p.x() * inverse_size)),
                   static_cast<std::int64_t>(std::floor(p.y() * inverse_size)),
                   static_cast<std::int64_t>(std::floor(p.z() * inverse_size)));
}

class VoxelIndex {
 public:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  explicit VoxelIndex(std::size_t expected = 1024) { rehash(capacityFor(expected)); }

  std::size_t size() const { return size_; }

  /// Index of `key`, inserting it (as index size()) when new; `inserted` tells which.
  std::uint32_t findOrInsert(std::uint64_t key, bool& inserted) {
    if (4 * (size_ + 1) > 3 * keys_.size()) rehash(keys_.size() * 2);
    std::size_t slot = slotOf(key);
    while (true) {
      if (keys_[slot] == kEmpty) {
        keys_[slot] = key;
        values_[slot] = static_cast<std::uint32_t>(size_++);
        inserted = true;
        return values_[slot];
      }
      if (keys_[slot] == key) {
        inserted = false;
        return values_[slot];
      }
      slot = (slot + 1) & (keys_.size() - 1);
    }
  }

  /// Asks the processor to load `key`'s first slot (a later findOrInsert or
  /// find of it then waits less on memory).
  void prefetch(std::uint64_t key) const {
    const std::size_t slot = slotOf(key);
    __builtin_prefetch(&keys_[slot]);
    __builtin_prefetch(&values_[slot]);
  }

  std::uint32_t find(std::uint64_t key) const {
    std::size_t slot = slotOf(key);
    while (true) {
      if (keys_[slot] == kEmpty) return kNone;
      if (keys_[slot] == key) return values_[slot];
      slot = (slot + 1) & (keys_.size() - 1);
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max();
  static std::size_t capacityFor(std::size_t n) {
    std::size_t c = 16;
    while (3 * c < 4 * n) c *= 2;
    return c;
  }
  std::size_t slotOf(std::uint64_t key) const {
    std::uint64_t h = key * 0x9E3779B97F4A7C15ull;
    h ^= h >> 29;
    return static_cast<std::size_t>(h) & (keys_.size() - 1);
  }
  void rehash(std::size_t capacity) {
    std::vector<std::uint64_t> old_keys(capacity, kEmpty);
    std::vector<std::uint32_t> old_values(capacity, 0);
    old_keys.swap(keys_);
    old_values.swap(values_);
    for (std::size_t s = 0; s < old_keys.size(); ++s) {
      if (old_keys[s] == kEmpty) continue;
      std::size_t slot = slotOf(old_keys[s]);
      while (keys_[slot] != kEmpty) slot = (slot + 1) & (keys_.size() - 1);
      keys_[slot] = old_keys[s];
      values_[slot] = old_values[s];
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> values_;
  std::size_t size_ = 0;
};

}  // namespace storey
