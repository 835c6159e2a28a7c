#include "odometry/voxel_map.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "types/voxel_hash.h"

namespace storey {

VoxelMap::VoxelMap(const VoxelMapConfig& config)
    : config_(config),
      inverse_size_(static_cast<float>(1.0 / config.voxel_size)),
      capacity_(static_cast<std::size_t>(std::max(config.max_points_per_voxel, 1))) {
  rebuildIndex(1024);
}

namespace {
std::size_t slotOfKey(std::uint64_t key, std::size_t mask) {
  return static_cast<std::size_t>(voxelHash(key)) & mask;
}
}  // namespace

const VoxelMap::Slot* VoxelMap::findSlot(Key key) const {
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = slotOfKey(key, mask);; i = (i + 1) & mask) {
    const Slot& slot = slots_[i];
    if (slot.key == key) return &slot;
    if (slot.key == kEmptyKey) return nullptr;
  }
}

VoxelMap::Slot& VoxelMap::findOrAddSlot(Key key) {
  if (2 * (voxel_count_ + 1) > slots_.size()) rebuildIndex(2 * slots_.size());
  const std::size_t mask = slots_.size() - 1;
  std::size_t i = slotOfKey(key, mask);
  for (; slots_[i].key != kEmptyKey; i = (i + 1) & mask)
    if (slots_[i].key == key) return slots_[i];
  std::uint32_t block = 0;
  if (!free_blocks_.empty()) {
    block = free_blocks_.back();
    free_blocks_.pop_back();
    block_keys_[block] = key;
  } else {
    block = static_cast<std::uint32_t>(block_keys_.size());
    block_keys_.push_back(key);
    points_.resize(points_.size() + capacity_);
  }
  ++voxel_count_;
  slots_[i] = {key, block, 0};
  return slots_[i];
}

void VoxelMap::rebuildIndex(std::size_t slots) {
  // The counts live in the slots: carry them over.
  std::vector<std::uint32_t> counts(block_keys_.size(), 0);
  for (const Slot& slot : slots_)
    if (slot.key != kEmptyKey) counts[slot.block] = slot.count;
  std::size_t size = 16;
  while (size < slots || size < 2 * voxel_count_) size *= 2;
  slots_.assign(size, Slot{kEmptyKey, 0, 0});
  const std::size_t mask = size - 1;
  for (std::size_t b = 0; b < block_keys_.size(); ++b) {
    if (block_keys_[b] == kEmptyKey) continue;
    std::size_t i = slotOfKey(block_keys_[b], mask);
    while (slots_[i].key != kEmptyKey) i = (i + 1) & mask;
    slots_[i] = {block_keys_[b], static_cast<std::uint32_t>(b), counts[b]};
  }
}

Eigen::Vector3i VoxelMap::cellOf(const Eigen::Vector3f& p) const {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() * inverse_size_)),
                         static_cast<int>(std::floor(p.y() * inverse_size_)),
                         static_cast<int>(std::floor(p.z() * inverse_size_)));
}

VoxelMap::Key VoxelMap::keyOf(std::int64_t x, std::int64_t y, std::int64_t z) const {
  const auto pack = [](std::int64_t v) {
    return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1FFFFF;
  };
  return (pack(x) << 42) | (pack(y) << 21) | pack(z);
}

VoxelMap::Key VoxelMap::keyOf(const Eigen::Vector3f& p) const {
  const Eigen::Vector3i c = cellOf(p);
  return keyOf(c.x(), c.y(), c.z());
}

void VoxelMap::insertPoint(const Eigen::Vector3f& p, const Eigen::Vector3f& view) {
  if (!p.allFinite()) return;
  const float min_spacing_squared =
      static_cast<float>(config_.min_point_spacing * config_.min_point_spacing);
  Slot& slot = findOrAddSlot(keyOf(p));
  if (slot.count >= capacity_) return;
  MapPoint* block = &points_[slot.block * capacity_];
  const bool too_close = std::any_of(block, block + slot.count, [&](const MapPoint& q) {
    return (q.p - p).squaredNorm() < min_spacing_squared;
  });
  if (too_close) return;
  block[slot.count++] = {p, view};
  ++point_count_;
}

void VoxelMap::insert(const std::vector<Eigen::Vector3f>& points_world) {
  for (const Eigen::Vector3f& p : points_world) insertPoint(p, Eigen::Vector3f::Zero());
}

void VoxelMap::insert(const std::vector<Eigen::Vector3f>& points_world,
                      const Eigen::Vector3d& sensor_world) {
  const Eigen::Vector3f sensor = sensor_world.cast<float>();
  for (const Eigen::Vector3f& p : points_world) {
    const Eigen::Vector3f to_sensor = sensor - p;
    const float norm = to_sensor.norm();
    insertPoint(p, norm > 1e-6f ? Eigen::Vector3f(to_sensor / norm) : Eigen::Vector3f::Zero());
  }
}

void VoxelMap::removeFar(const Eigen::Vector3d& sensor_world) {
  const double max_squared = config_.max_range * config_.max_range;
  bool removed = false;
  for (const Slot& slot : slots_) {
    if (slot.key == kEmptyKey) continue;
    const bool far =
        slot.count > 0 &&
        (points_[slot.block * capacity_].p.cast<double>() - sensor_world).squaredNorm() >
            max_squared;
    if (far || slot.count == 0) {
      point_count_ -= slot.count;
      --voxel_count_;
      block_keys_[slot.block] = kEmptyKey;
      free_blocks_.push_back(slot.block);
      removed = true;
    }
  }
  // Freed blocks are reused highest first, whatever the slots' order.
  std::sort(free_blocks_.begin(), free_blocks_.end());
  if (removed) rebuildIndex(slots_.size());
}

void VoxelMap::transform(const Pose& T) {
  std::vector<MapPoint> points;
  points.reserve(point_count_);
  const Eigen::Matrix3f R = T.rotationMatrix().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  for (const Slot& slot : slots_) {
    if (slot.key == kEmptyKey) continue;
    for (std::uint32_t i = 0; i < slot.count; ++i) {
      const MapPoint& m = points_[slot.block * capacity_ + i];
      points.push_back({R * m.p + t, R * m.view});
    }
  }
  points_.clear();
  block_keys_.clear();
  free_blocks_.clear();
  voxel_count_ = 0;
  point_count_ = 0;
  slots_.clear();
  rebuildIndex(1024);
  for (const MapPoint& m : points) insertPoint(m.p, m.view);
}

int VoxelMap::nearest(const Eigen::Vector3f& query, int k, float max_distance, Eigen::Vector3f* out,
                      Eigen::Vector3f* views_out) const {
  k = std::clamp(k, 0, kMaxNeighbours);
  if (k == 0) return 0;
  // Insertion into a small sorted array: k is tiny, the candidates a few hundred.
  float best_d2[kMaxNeighbours];
  const MapPoint* best[kMaxNeighbours];
  int found = 0;
  float worst = max_distance * max_distance;
  const Eigen::Vector3i c = cellOf(query);
  // How far the query is from its cell's lower and upper faces on each axis,
  // less a margin for the rounding of a point's cell: a neighbour cell
  // farther than the k-th candidate so far holds no better point and is
  // skipped (so is its hash lookup). The query's own cell comes first, so
  // the candidates are near before the neighbour cells are tested.
  constexpr float kMargin = 1e-3f;  // [m], far above float rounding at building scale
  const float size = 1.0f / inverse_size_;
  float gap[3][3];  // [axis][offset + 1]: the per-axis distance to the neighbour cell
  for (int a = 0; a < 3; ++a) {
    const float lower = static_cast<float>(c[a]) * size;
    gap[a][0] = std::max(0.0f, query[a] - lower - kMargin);
    gap[a][1] = 0.0f;
    gap[a][2] = std::max(0.0f, lower + size - query[a] - kMargin);
  }
  const auto search = [&](int dx, int dy, int dz) {
    const float box_d2 = gap[0][dx + 1] * gap[0][dx + 1] + gap[1][dy + 1] * gap[1][dy + 1] +
                         gap[2][dz + 1] * gap[2][dz + 1];
    if (box_d2 > worst) return;
    const Slot* slot = findSlot(keyOf(c.x() + dx, c.y() + dy, c.z() + dz));
    if (slot == nullptr) return;
    const MapPoint* block = &points_[slot->block * capacity_];
    for (std::uint32_t j = 0; j < slot->count; ++j) {
      const MapPoint& m = block[j];
      const float d2 = (m.p - query).squaredNorm();
      if (d2 > worst) continue;
      int i = found < k ? found++ : k - 1;
      while (i > 0 && best_d2[i - 1] > d2) {
        best_d2[i] = best_d2[i - 1];
        best[i] = best[i - 1];
        --i;
      }
      best_d2[i] = d2;
      best[i] = &m;
      if (found == k) worst = best_d2[k - 1];
    }
  };
  search(0, 0, 0);
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz)
        if (dx != 0 || dy != 0 || dz != 0) search(dx, dy, dz);
  for (int i = 0; i < found; ++i) out[i] = best[i]->p;
  if (views_out)
    for (int i = 0; i < found; ++i) views_out[i] = best[i]->view;
  return found;
}

std::vector<Eigen::Vector3f> VoxelMap::nearest(const Eigen::Vector3f& query, int k,
                                               float max_distance) const {
  Eigen::Vector3f buffer[kMaxNeighbours];
  const int found = nearest(query, k, max_distance, buffer);
  return std::vector<Eigen::Vector3f>(buffer, buffer + found);
}

namespace {

void meanAndCovariance(const Eigen::Vector3f* points, int count, Eigen::Vector3d& mean,
                       Eigen::Matrix3d& covariance) {
  mean.setZero();
  for (int i = 0; i < count; ++i) mean += points[i].cast<double>();
  mean /= static_cast<double>(count);
  covariance.setZero();
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d d = points[i].cast<double>() - mean;
    covariance += d * d.transpose();
  }
  covariance /= static_cast<double>(count);
}

}  // namespace

PlaneFit fitPlane(const Eigen::Vector3f* points, int count, double max_distance) {
  PlaneFit fit;
  if (count < 3) return fit;
  Eigen::Vector3d mean;
  Eigen::Matrix3d covariance;
  meanAndCovariance(points, count, mean, covariance);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance);
  // Eigenvalues ascending: the smallest one's vector is the normal; the
  // points must also spread in two directions: a neighbourhood taken from one
  // ring of a sparse LiDAR is nearly a line and leaves the normal undefined.
  if (solver.eigenvalues()(1) < 1e-8 || solver.eigenvalues()(1) < 0.01 * solver.eigenvalues()(2))
    return fit;
  fit.normal = solver.eigenvectors().col(0).normalized();
  fit.d = fit.normal.dot(mean);
  fit.thickness = std::sqrt(std::max(solver.eigenvalues()(0), 0.0));
  for (int i = 0; i < count; ++i)
    if (std::abs(fit.normal.dot(points[i].cast<double>()) - fit.d) > max_distance) return fit;
  fit.valid = true;
  return fit;
}

PlaneFit fitPlaneLargestFace(const Eigen::Vector3f* points, int count, double max_distance,
                             int min_inliers, std::uint32_t* inliers,
                             const Eigen::Vector3f* query) {
  PlaneFit none;
  if (count < 3 || count > 32 || count < min_inliers) return none;
  const auto fitMask = [&](std::uint32_t mask) {
    Eigen::Vector3f subset[32];
    int n = 0;
    for (int i = 0; i < count; ++i)
      if (mask & (1u << i)) subset[n++] = points[i];
    return n >= 3 ? fitPlane(subset, n, max_distance) : PlaneFit{};
  };
  const std::uint32_t all = count == 32 ? ~0u : (1u << count) - 1u;
  // Most neighbourhoods are one surface: the least-squares plane of all the
  // points is then within half the tolerance of every one of them.
  const PlaneFit whole = fitPlane(points, count, 0.5 * max_distance);
  if (whole.valid) {
    if (inliers != nullptr) *inliers = all;
    return whole;
  }
  Eigen::Vector3d p[32];
  for (int i = 0; i < count; ++i) p[i] = points[i].cast<double>();
  const Eigen::Vector3d q =
      query != nullptr ? Eigen::Vector3d(query->cast<double>()) : Eigen::Vector3d::Zero();
  // With a query, a plane must pass within max_distance of it.
  const auto reaches = [&](const Eigen::Vector3d& n, double d) {
    return query == nullptr || std::abs(n.dot(q) - d) <= max_distance;
  };
  // The face: of the planes through three points, the one with the most
  // points within half the tolerance (about the points' own noise; ties: the
  // smaller sum of their squared distances). Near a tread's edge a plane
  // sloping across the tread and the riser below it keeps every point within
  // the whole tolerance, as the least-squares plane did, but not within half.
  const double tight = 0.5 * max_distance;
  const auto maskWithin = [&](const Eigen::Vector3d& n, double d, double* sum_squares) {
    std::uint32_t mask = 0;
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
      const double e = n.dot(p[i]) - d;
      if (std::abs(e) <= tight) {
        mask |= 1u << i;
        sum += e * e;
      }
    }
    if (sum_squares != nullptr) *sum_squares = sum;
    return mask;
  };
  std::uint32_t best_mask = 0;
  int best_count = 0;
  double best_sum = 0.0;
  for (int a = 0; a < count; ++a)
    for (int b = a + 1; b < count; ++b)
      for (int c = b + 1; c < count; ++c) {
        const Eigen::Vector3d cross = (p[b] - p[a]).cross(p[c] - p[a]);
        const double norm = cross.norm();
        if (norm < 1e-6) continue;  // (nearly) collinear: no plane
        const Eigen::Vector3d n = cross / norm;
        // The query's own face: not the next tread up or down the flight.
        const double d = n.dot(p[a]);
        if (!reaches(n, d)) continue;
        double sum = 0.0;
        const std::uint32_t mask = maskWithin(n, d, &sum);
        const int k = __builtin_popcount(mask);
        if (k > best_count || (k == best_count && sum < best_sum)) {
          best_mask = mask;
          best_count = k;
          best_sum = sum;
        }
      }
  if (best_count < std::max(min_inliers, 3)) return none;
  // Refit on the face's points, take its points again, refit.
  PlaneFit fit = fitMask(best_mask);
  if (!fit.valid || !reaches(fit.normal, fit.d)) return none;
  const std::uint32_t again = maskWithin(fit.normal, fit.d, nullptr);
  if (again != best_mask && __builtin_popcount(again) >= min_inliers) {
    const PlaneFit refit = fitMask(again);
    if (refit.valid && reaches(refit.normal, refit.d)) {
      fit = refit;
      best_mask = again;
    }
  }
  if (__builtin_popcount(best_mask) < min_inliers) return none;
  if (inliers != nullptr) *inliers = best_mask;
  return fit;
}

LineFit fitLine(const Eigen::Vector3f* points, int count, double min_ratio) {
  LineFit fit;
  if (count < 2) return fit;
  Eigen::Vector3d mean;
  Eigen::Matrix3d covariance;
  meanAndCovariance(points, count, mean, covariance);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance);
  fit.point = mean;
  fit.direction = solver.eigenvectors().col(2).normalized();
  fit.thickness = std::sqrt(std::max(solver.eigenvalues()(0) + solver.eigenvalues()(1), 0.0));
  fit.valid = solver.eigenvalues()(2) > min_ratio * solver.eigenvalues()(1) &&
              solver.eigenvalues()(2) > 1e-8;
  return fit;
}

}  // namespace storey
