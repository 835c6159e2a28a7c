#pragma once
/// A growing array stored in chunks of a fixed number of elements, for the
/// map's per-voxel accumulators: growing never copies and never holds twice
/// the elements (as a std::vector's reallocation does), so memory follows
/// the size; read back in order, the chunks can be freed front to back.
#include <cstddef>
#include <memory>
#include <vector>

namespace storey {

template <typename T, std::size_t kChunk = std::size_t{1} << 18>
class ChunkedArray {
 public:
  std::size_t size() const { return size_; }

  void push_back(const T& value) {
    if (size_ == chunks_.size() * kChunk) chunks_.push_back(std::make_unique<T[]>(kChunk));
    chunks_[size_ / kChunk][size_ % kChunk] = value;
    ++size_;
  }

  T& operator[](std::size_t i) { return chunks_[i / kChunk][i % kChunk]; }
  const T& operator[](std::size_t i) const { return chunks_[i / kChunk][i % kChunk]; }

  /// Frees the chunks wholly before element `i` (read in order, done with);
  /// those elements must not be accessed any more.
  void releaseBefore(std::size_t i) {
    for (; released_ < i / kChunk && released_ < chunks_.size(); ++released_)
      chunks_[released_].reset();
  }

 private:
  std::vector<std::unique_ptr<T[]>> chunks_;
  std::size_t size_ = 0;
  std::size_t released_ = 0;  ///< chunks freed, from the front
};

}  // namespace storey
