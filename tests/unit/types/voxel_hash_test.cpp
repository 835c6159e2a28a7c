// The voxel indices: dense indices in insertion order, the same for the
// 12-byte-slot VoxelIndex and the 4-byte-slot VoxelIndexOverKeys through
// their growth (rehashes), with keys that collide in their home slots.
#include "types/voxel_hash.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "map/chunked_array.h"

namespace storey {
namespace {

TEST(VoxelHash, BothIndicesNumberVoxelsInFirstSeenOrderThroughGrowth) {
  std::mt19937 rng(21);
  std::uniform_int_distribution<int> coordinate(-300, 300);
  std::vector<std::uint64_t> stream;
  for (int i = 0; i < 200000; ++i)
    stream.push_back(packVoxel(coordinate(rng), coordinate(rng), coordinate(rng) / 50));
  VoxelIndex wide(16);
  ChunkedArray<std::uint64_t, 1024> keys;
  VoxelIndexOverKeys<ChunkedArray<std::uint64_t, 1024>> compact(keys, 16);
  std::vector<std::uint64_t> first_seen;
  for (const std::uint64_t key : stream) {
    bool wide_new = false, compact_new = false;
    const std::uint32_t a = wide.findOrInsert(key, wide_new);
    if (key % 3 == 0) {
      compact.prefetch(key);
      compact.prefetchKey(key);
    }
    const std::uint32_t b = compact.findOrInsert(key, compact_new);
    ASSERT_EQ(a, b);
    ASSERT_EQ(wide_new, compact_new);
    if (wide_new) {
      ASSERT_EQ(a, first_seen.size());
      first_seen.push_back(key);
    } else {
      ASSERT_EQ(first_seen[a], key);
    }
  }
  ASSERT_GT(first_seen.size(), 50000u);  // grew through many doublings
  EXPECT_EQ(compact.size(), first_seen.size());
  ASSERT_EQ(keys.size(), first_seen.size());
  for (std::size_t v = 0; v < first_seen.size(); ++v) {
    ASSERT_EQ(keys[v], first_seen[v]);
    ASSERT_EQ(wide.find(first_seen[v]), v);
  }
  EXPECT_EQ(wide.find(packVoxel(1000, 1000, 1000)), VoxelIndex::kNone);
}

}  // namespace
}  // namespace storey
