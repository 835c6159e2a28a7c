#pragma once
/// Compact open-addressing hashes from a voxel's integer coordinates to a
/// dense index (0, 1, 2, ... in insertion order), grown (doubled) at
/// three-quarter load: VoxelIndex, 12 bytes a slot (16-32 bytes an entry),
/// used by the storey stage's subsampling, the odometry's feature
/// downsampling and the SRP extraction's; VoxelIndexOverKeys, 4 bytes a slot
/// over the caller's array of keys, used by map assembly (millions of voxels).
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

/// The hash of a packed voxel key: MurmurHash3's 64-bit finaliser, so every
/// bit of all three coordinates reaches the low bits a table's slot is taken
/// from. (A single Fibonacci multiply with the high bits folded down left the
/// x coordinate, the key's top bits, out of the slot of any table under 2^22
/// slots: scans' voxels along x then shared probe chains.)
inline std::uint64_t voxelHash(std::uint64_t key) {
  std::uint64_t h = key;
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ull;
  h ^= h >> 33;
  return h;
}

/// Smallest power-of-two table (>= 16 slots) that holds n entries at <= 3/4 load.
inline std::size_t voxelTableCapacity(std::size_t n) {
  std::size_t c = 16;
  while (3 * c < 4 * n) c *= 2;
  return c;
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
  static std::size_t capacityFor(std::size_t n) { return voxelTableCapacity(n); }
  std::size_t slotOf(std::uint64_t key) const {
    return static_cast<std::size_t>(voxelHash(key)) & (keys_.size() - 1);
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

/// VoxelIndex with 4-byte slots for tables of many millions of voxels (the
/// map's 2 cm voxels): the keys live in an array the index appends to (keys[i]
/// is the key of index i, which the caller keeps anyway), and a slot holds
/// only the index, so the table is a third of VoxelIndex's. A lookup reads
/// the key of each index it probes (prefetchKey() asks for it ahead).
/// KeyArray: size(), push_back(std::uint64_t), operator[] (e.g. ChunkedArray).
template <typename KeyArray>
class VoxelIndexOverKeys {
 public:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  /// `keys` must be empty and outlive the index.
  VoxelIndexOverKeys(KeyArray& keys, std::size_t expected)
      : keys_(keys), slots_(voxelTableCapacity(expected), kNone) {}

  std::size_t size() const { return keys_.size(); }

  std::uint32_t findOrInsert(std::uint64_t key, bool& inserted) {
    if (4 * (keys_.size() + 1) > 3 * slots_.size()) rehash(slots_.size() * 2);
    std::size_t slot = slotOf(key);
    while (true) {
      const std::uint32_t v = slots_[slot];
      if (v == kNone) {
        const auto index = static_cast<std::uint32_t>(keys_.size());
        keys_.push_back(key);
        slots_[slot] = index;
        inserted = true;
        return index;
      }
      if (keys_[v] == key) {
        inserted = false;
        return v;
      }
      slot = (slot + 1) & (slots_.size() - 1);
    }
  }

  /// Asks the processor to load `key`'s first slot.
  void prefetch(std::uint64_t key) const { __builtin_prefetch(&slots_[slotOf(key)]); }
  /// After prefetch(key): asks for the key of the index in its first slot.
  void prefetchKey(std::uint64_t key) const {
    const std::uint32_t v = slots_[slotOf(key)];
    if (v != kNone) __builtin_prefetch(&keys_[v]);
  }

  /// Frees the table (the keys stay); the index must not be used after.
  void release() { std::vector<std::uint32_t>().swap(slots_); }

 private:
  std::size_t slotOf(std::uint64_t key) const {
    return static_cast<std::size_t>(voxelHash(key)) & (slots_.size() - 1);
  }
  void rehash(std::size_t capacity) {
    slots_.assign(capacity, kNone);
    for (std::size_t v = 0; v < keys_.size(); ++v) {
      std::size_t slot = slotOf(keys_[v]);
      while (slots_[slot] != kNone) slot = (slot + 1) & (slots_.size() - 1);
      slots_[slot] = static_cast<std::uint32_t>(v);
    }
  }

  KeyArray& keys_;
  std::vector<std::uint32_t> slots_;
};

}  // namespace storey
