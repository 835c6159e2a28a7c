#include "odometry/features.h"

#include "common/parallel_chunks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>

namespace storey {

const char* toString(FeatureReject reason) {
  switch (reason) {
    case FeatureReject::kRingGap:
      return "ring gap";
    case FeatureReject::kOccluded:
      return "occluded";
    case FeatureReject::kParallelBeam:
      return "parallel beam";
    case FeatureReject::kCount:
      break;
  }
  return "unknown";
}

namespace {

constexpr std::uint8_t kEligible = 0xFF;

/// One ring's points in firing order, with what the extraction needs.
struct Ring {
  std::vector<std::uint32_t> index;  // into scan.points
  std::vector<float> range;
  std::vector<int> segment;  // contiguous runs without a gap
  std::vector<float> smoothness;
  std::vector<std::uint8_t> status;  // kEligible or a FeatureReject value
};

std::vector<std::vector<std::uint32_t>> groupByRing(const Scan& scan) {
  std::uint16_t max_ring = 0;
  for (const ScanPoint& p : scan.points) max_ring = std::max(max_ring, p.ring);
  std::vector<std::vector<std::uint32_t>> rings(scan.points.empty() ? 0 : max_ring + 1u);
  for (std::uint32_t i = 0; i < scan.points.size(); ++i) rings[scan.points[i].ring].push_back(i);
  const auto earlier = [&](std::uint32_t a, std::uint32_t b) {
    return scan.points[a].time < scan.points[b].time;
  };
  for (auto& ring : rings) {  // drivers write points in firing order: usually sorted already
    if (!std::is_sorted(ring.begin(), ring.end(), earlier))
      std::stable_sort(ring.begin(), ring.end(), earlier);
  }
  return rings;
}

void segmentRing(const Scan& scan, const FeatureConfig& config, Ring& ring) {
  const std::size_t n = ring.index.size();
  std::vector<float> steps(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i)
    steps[i] = scan.points[ring.index[i + 1]].time - scan.points[ring.index[i]].time;
  std::vector<float> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const float max_step = static_cast<float>(config.max_gap_factor) * sorted[sorted.size() / 2];
  ring.segment.assign(n, 0);
  for (std::size_t i = 1; i < n; ++i)
    ring.segment[i] = ring.segment[i - 1] + (steps[i - 1] > max_step ? 1 : 0);
}

void markUnreliable(const Scan& scan, const FeatureConfig& config, Ring& ring) {
  const int k = config.neighbours;
  const int n = static_cast<int>(ring.index.size());
  ring.status.assign(n, kEligible);
  for (int i = 0; i < n; ++i) {
    if (i < k || i + k >= n || ring.segment[i - k] != ring.segment[i] ||
        ring.segment[i + k] != ring.segment[i])
      ring.status[i] = static_cast<std::uint8_t>(FeatureReject::kRingGap);
  }
  const auto mark = [&](int from, int to, FeatureReject reason) {
    for (int j = std::max(from, 0); j <= std::min(to, n - 1); ++j)
      if (ring.status[j] == kEligible) ring.status[j] = static_cast<std::uint8_t>(reason);
  };
  for (int i = 0; i + 1 < n; ++i) {
    if (ring.segment[i] != ring.segment[i + 1]) continue;
    const float jump = ring.range[i] - ring.range[i + 1];
    if (jump > config.occlusion_gap) mark(i - k, i, FeatureReject::kOccluded);  // i behind
    if (-jump > config.occlusion_gap)
      mark(i + 1, i + 1 + k, FeatureReject::kOccluded);  // i+1 behind
  }
  for (int i = 1; i + 1 < n; ++i) {
    const float limit = static_cast<float>(config.parallel_ratio) * ring.range[i];
    if (std::abs(ring.range[i - 1] - ring.range[i]) > limit &&
        std::abs(ring.range[i + 1] - ring.range[i]) > limit &&
        ring.segment[i - 1] == ring.segment[i + 1])
      mark(i, i, FeatureReject::kParallelBeam);
  }
  (void)scan;
}

/// Smoothness of each point: |sum of the offsets to its 2k neighbours| / sum
/// of their lengths. Computed offset by offset over the whole ring from
/// coordinate arrays, so that the loop over points vectorises (features.cpp
/// is built with -fno-math-errno for the square roots); each point's sums
/// add the same terms in the same order as one point at a time would.
void computeSmoothness(const Scan& scan, const FeatureConfig& config, Ring& ring) {
  const int k = config.neighbours;
  const int n = static_cast<int>(ring.index.size());
  ring.smoothness.assign(n, 0.0f);
  if (n < 2 * k + 1) return;
  std::vector<float> x(n), y(n), z(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = scan.points[ring.index[i]].p;
    x[i] = p.x();
    y[i] = p.y();
    z[i] = p.z();
  }
  const int first = k, end = n - k;  // points with k neighbours on each side
  std::vector<float> sum_x(n, 0.0f), sum_y(n, 0.0f), sum_z(n, 0.0f), length(n, 0.0f);
  for (int j = -k; j <= k; ++j) {
    for (int i = first; i < end; ++i) {
      const float dx = x[i + j] - x[i];
      const float dy = y[i + j] - y[i];
      const float dz = z[i + j] - z[i];
      sum_x[i] += dx;
      sum_y[i] += dy;
      sum_z[i] += dz;
      length[i] += std::sqrt(dx * dx + (dy * dy + dz * dz));  // Eigen's squaredNorm order
    }
  }
  for (int i = first; i < end; ++i) {
    if (ring.status[i] == static_cast<std::uint8_t>(FeatureReject::kRingGap)) continue;
    const float sum_norm =
        std::sqrt(sum_x[i] * sum_x[i] + (sum_y[i] * sum_y[i] + sum_z[i] * sum_z[i]));
    ring.smoothness[i] = length[i] > 0.0f ? sum_norm / length[i] : 0.0f;
  }
}

void selectFeatures(const Scan& scan, const FeatureConfig& config, const Ring& ring,
                    std::vector<Eigen::Vector3f>& edges, std::vector<Eigen::Vector3f>& planes,
                    FeatureSet& result) {
  const int n = static_cast<int>(ring.index.size());
  std::vector<int> eligible;
  for (int i = 0; i < n; ++i)
    if (ring.status[i] == kEligible) eligible.push_back(i);
  if (eligible.empty()) return;
  std::vector<bool> suppressed(n, false);
  const int sectors = std::max(config.sectors, 1);
  std::vector<std::uint64_t> edge_keys, plane_keys;
  // Largest smoothness (sharpest) first, ties by position: integer sorts on
  // (inverted smoothness bits, index) keys (a smoothness is >= 0, so its float
  // bits order as it does). Only the edge candidates (above edge_threshold)
  // and the planar ones (below plane_threshold, which is lower) are sorted:
  // in the order of all points they are its two ends, in the same order.
  const auto keyOf = [&](int i) {
    std::uint32_t bits;
    std::memcpy(&bits, &ring.smoothness[i], sizeof bits);
    return (static_cast<std::uint64_t>(~bits) << 32) | static_cast<std::uint32_t>(i);
  };
  const auto indexOf = [](std::uint64_t key) { return static_cast<int>(key & 0xFFFFFFFFu); };
  for (int s = 0; s < sectors; ++s) {
    const std::size_t begin = eligible.size() * s / sectors;
    const std::size_t end = eligible.size() * (s + 1) / sectors;
    edge_keys.clear();
    plane_keys.clear();
    for (std::size_t e = begin; e < end; ++e) {
      const int i = eligible[e];
      if (ring.smoothness[i] > config.edge_threshold) edge_keys.push_back(keyOf(i));
      if (ring.smoothness[i] < config.plane_threshold) plane_keys.push_back(keyOf(i));
    }
    result.edge_candidates += static_cast<std::int64_t>(edge_keys.size());
    if (config.max_edges_per_sector > 0) {
      std::sort(edge_keys.begin(), edge_keys.end());
      int picked = 0;
      for (std::uint64_t key : edge_keys) {
        const int i = indexOf(key);
        if (suppressed[i] || picked >= config.max_edges_per_sector) continue;
        edges.push_back(scan.points[ring.index[i]].p);
        ++picked;
        for (int j = std::max(i - config.neighbours, 0);
             j <= std::min(i + config.neighbours, n - 1); ++j)
          if (ring.segment[j] == ring.segment[i]) suppressed[j] = true;
      }
    }
    std::sort(plane_keys.begin(), plane_keys.end());
    for (std::uint64_t key : plane_keys) planes.push_back(scan.points[ring.index[indexOf(key)]].p);
    result.plane_candidates += static_cast<std::int64_t>(plane_keys.size());
  }
}

}  // namespace

FeatureSet extractFeatures(const Scan& scan, const FeatureConfig& config,
                           const ParallelChunks* parallel) {
  std::vector<std::vector<std::uint32_t>> rings = groupByRing(scan);
  // Each ring on its own (in parallel when asked), joined in ring order: the
  // same features whatever the number of threads.
  struct RingFeatures {
    std::vector<Eigen::Vector3f> edges, planes;
    FeatureSet counts;
  };
  std::vector<RingFeatures> parts(rings.size());
  const int min_points = 2 * config.neighbours + 2;
  const auto extractRing = [&](std::size_t r) {
    RingFeatures& part = parts[r];
    std::vector<std::uint32_t>& indices = rings[r];
    if (static_cast<int>(indices.size()) < min_points) {
      part.counts.rejected[static_cast<std::size_t>(FeatureReject::kRingGap)] +=
          static_cast<std::int64_t>(indices.size());
      return;
    }
    Ring ring;
    ring.index = std::move(indices);
    ring.range.resize(ring.index.size());
    for (std::size_t i = 0; i < ring.index.size(); ++i)
      ring.range[i] = scan.points[ring.index[i]].p.norm();
    segmentRing(scan, config, ring);
    markUnreliable(scan, config, ring);
    computeSmoothness(scan, config, ring);
    for (std::uint8_t status : ring.status)
      if (status != kEligible) ++part.counts.rejected[status];
    selectFeatures(scan, config, ring, part.edges, part.planes, part.counts);
  };
  if (parallel != nullptr && parallel->threads() > 1) {
    parallel->run(rings.size(), extractRing);
  } else {
    for (std::size_t r = 0; r < rings.size(); ++r) extractRing(r);
  }
  FeatureSet result;
  std::vector<Eigen::Vector3f> edges, planes;
  for (const RingFeatures& part : parts) {
    edges.insert(edges.end(), part.edges.begin(), part.edges.end());
    planes.insert(planes.end(), part.planes.begin(), part.planes.end());
    for (std::size_t i = 0; i < result.rejected.size(); ++i)
      result.rejected[i] += part.counts.rejected[i];
    result.edge_candidates += part.counts.edge_candidates;
    result.plane_candidates += part.counts.plane_candidates;
  }
  result.edges = voxelDownsample(edges, config.edge_voxel_size);
  result.planes = voxelDownsample(planes, config.plane_voxel_size);
  return result;
}

}  // namespace storey
