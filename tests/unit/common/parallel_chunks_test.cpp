// ParallelChunks: every chunk runs once, on one thread or several, and an
// exception in a chunk comes out of run().
#include "common/parallel_chunks.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

namespace storey {
namespace {

TEST(ParallelChunks, EveryChunkRunsOnceWhateverTheThreads) {
  for (int threads : {0, 1, 2, 4}) {
    const ParallelChunks parallel(threads);
    EXPECT_GE(parallel.threads(), 1);
    if (threads > 0) {
      EXPECT_EQ(parallel.threads(), threads);
    }
    std::vector<std::atomic<int>> runs(1000);
    parallel.run(runs.size(), [&](std::size_t i) { ++runs[i]; });
    for (std::size_t i = 0; i < runs.size(); ++i)
      ASSERT_EQ(runs[i].load(), 1) << threads << " " << i;
    parallel.run(0, [&](std::size_t) { FAIL() << "no chunk to run"; });
  }
}

TEST(ParallelChunks, AnExceptionInAChunkComesOut) {
  for (int threads : {1, 2}) {
    const ParallelChunks parallel(threads);
    EXPECT_THROW(parallel.run(64,
                              [](std::size_t i) {
                                if (i == 17) throw std::runtime_error("chunk 17");
                              }),
                 std::runtime_error);
  }
}

}  // namespace
}  // namespace storey
