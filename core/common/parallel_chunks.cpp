#include "common/parallel_chunks.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace storey {

struct ParallelChunks::Arena {
  explicit Arena(int threads) : arena(threads) {}
  tbb::task_arena arena;
};

ParallelChunks::ParallelChunks(int threads) {
  threads_ = threads > 0 ? threads : std::max(1, tbb::this_task_arena::max_concurrency());
  if (threads_ > 1) arena_ = std::make_unique<Arena>(threads_);
}

ParallelChunks::~ParallelChunks() = default;

void ParallelChunks::run(std::size_t count, const std::function<void(std::size_t)>& fn) const {
  if (!arena_ || count <= 1) {
    for (std::size_t i = 0; i < count; ++i) fn(i);
    return;
  }
  arena_->arena.execute(
      [&] { tbb::parallel_for(std::size_t{0}, count, [&](std::size_t i) { fn(i); }); });
}

}  // namespace storey
