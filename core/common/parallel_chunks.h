#pragma once
/// Runs fn(0), fn(1), ..., fn(count - 1) on up to `threads` threads (TBB, in a
/// task arena of that size kept for the object's life; in the calling thread
/// when threads is 1) and returns when all are done. The chunks must write to
/// places of their own, so a caller that splits its work into chunks of a
/// fixed size and joins their results in chunk order gets the same result
/// whatever the number of threads. An exception in a chunk comes out of run().
#include <cstddef>
#include <functional>
#include <memory>

namespace storey {

class ParallelChunks {
 public:
  /// threads: 0 = every core, 1 = the calling thread only.
  explicit ParallelChunks(int threads);
  ~ParallelChunks();
  ParallelChunks(const ParallelChunks&) = delete;
  ParallelChunks& operator=(const ParallelChunks&) = delete;

  int threads() const { return threads_; }
  void run(std::size_t count, const std::function<void(std::size_t)>& fn) const;

 private:
  struct Arena;
  int threads_ = 1;
  std::unique_ptr<Arena> arena_;  ///< null with one thread
};

}  // namespace storey
