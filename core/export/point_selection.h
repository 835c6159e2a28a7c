#pragma once
/// The points a map writer writes: the whole cloud, or the listed indices.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace storey {

class PointSelection {
 public:
  /// `indices` null: every one of `cloud_size` points, in order.
  PointSelection(std::size_t cloud_size, const std::vector<std::uint32_t>* indices)
      : indices_(indices), size_(indices ? indices->size() : cloud_size) {}
  std::size_t size() const { return size_; }
  /// Cloud index of the k-th written point.
  std::size_t at(std::size_t k) const { return indices_ ? (*indices_)[k] : k; }

 private:
  const std::vector<std::uint32_t>* indices_;
  std::size_t size_;
};

}  // namespace storey
