// core/map/chunked_array.h: the map builder's growing accumulator storage.
#include "map/chunked_array.h"

#include <gtest/gtest.h>

namespace storey {
namespace {

TEST(ChunkedArray, GrowsAcrossChunksKeepingEveryElementInPlace) {
  ChunkedArray<int, 4> a;
  EXPECT_EQ(a.size(), 0u);
  for (int i = 0; i < 11; ++i) a.push_back(10 * i);
  ASSERT_EQ(a.size(), 11u);
  const int* third = &a[2];
  for (int i = 11; i < 40; ++i) a.push_back(10 * i);  // no reallocation moves the elements
  EXPECT_EQ(third, &a[2]);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], static_cast<int>(10 * i));
  a[7] += 1;
  EXPECT_EQ(a[7], 71);
}

TEST(ChunkedArray, ReleasingTheReadPartKeepsTheRest) {
  ChunkedArray<int, 4> a;
  for (int i = 0; i < 10; ++i) a.push_back(i);
  a.releaseBefore(9);  // frees chunks [0, 4) and [4, 8); 8 and 9 stay
  EXPECT_EQ(a[8], 8);
  EXPECT_EQ(a[9], 9);
  a.releaseBefore(5);  // nothing more (already released)
  EXPECT_EQ(a.size(), 10u);
}

}  // namespace
}  // namespace storey
