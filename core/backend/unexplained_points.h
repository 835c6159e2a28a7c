#pragma once
/// The points of a scan that no detected plane explains yet, and the inlier
/// test every plane's refinement runs over all of them (srp_extraction.cpp).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace storey::backend {

/// The points no detected plane explains yet, in scan order, as arrays per
/// coordinate (the inlier test of every plane runs over all of them).
struct UnexplainedPoints {
  std::vector<float> x, y, z;        ///< the points' coordinates (as scanned: float)
  std::vector<std::uint32_t> index;  ///< into the scan's points
  float max_abs = 0.0f;              ///< largest |coordinate| (bounds the float test's error)

  explicit UnexplainedPoints(const std::vector<Eigen::Vector3f>& points) {
    x.reserve(points.size());
    y.reserve(points.size());
    z.reserve(points.size());
    index.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      x.push_back(points[i].x());
      y.push_back(points[i].y());
      z.push_back(points[i].z());
      index.push_back(static_cast<std::uint32_t>(i));
      max_abs = std::max(
          {max_abs, std::abs(points[i].x()), std::abs(points[i].y()), std::abs(points[i].z())});
    }
  }

  /// The points within `threshold` of the plane n.p = d (their positions j
  /// here, in order) into `out`.
  void within(const Eigen::Vector3d& n, double d, double threshold,
              std::vector<std::uint32_t>& out) const {
    out.resize(x.size());
    std::uint32_t* __restrict o = out.data();
    std::size_t kept = 0;
    forEachBlock(n, d, threshold,
                 [&](std::size_t base, std::size_t m, const std::int32_t* inside, bool any_inside) {
                   if (!any_inside) return;
                   // Branch-free: every j is written, the count only grows for an inlier.
                   for (std::size_t j = 0; j < m; ++j) {
                     o[kept] = static_cast<std::uint32_t>(base + j);
                     kept += inside[j] != 0 ? 1 : 0;
                   }
                 });
    out.resize(kept);
  }

  /// within() and then the removal of those points, in one pass: the points
  /// within `threshold` of the plane leave the arrays (the others keep their
  /// order); their coordinates go to `inliers` and their scan indices to
  /// `inlier_index`, in order.
  void extract(const Eigen::Vector3d& n, double d, double threshold,
               std::vector<Eigen::Vector3d>& inliers, std::vector<std::uint32_t>& inlier_index) {
    inliers.clear();
    inlier_index.clear();
    std::size_t kept = 0;
    forEachBlock(n, d, threshold,
                 [&](std::size_t base, std::size_t m, const std::int32_t* inside, bool any_inside) {
                   if (!any_inside) {  // the whole block stays: moved down as one
                     if (kept != base) {
                       const auto from = static_cast<std::ptrdiff_t>(base),
                                  to = static_cast<std::ptrdiff_t>(kept),
                                  size = static_cast<std::ptrdiff_t>(m);
                       std::copy(x.begin() + from, x.begin() + from + size, x.begin() + to);
                       std::copy(y.begin() + from, y.begin() + from + size, y.begin() + to);
                       std::copy(z.begin() + from, z.begin() + from + size, z.begin() + to);
                       std::copy(index.begin() + from, index.begin() + from + size,
                                 index.begin() + to);
                     }
                     kept += m;
                     return;
                   }
                   for (std::size_t j = base; j < base + m; ++j) {
                     if (inside[j - base] != 0) {
                       inliers.emplace_back(x[j], y[j], z[j]);
                       inlier_index.push_back(index[j]);
                     } else {
                       x[kept] = x[j];
                       y[kept] = y[j];
                       z[kept] = z[j];
                       index[kept] = index[j];
                       ++kept;
                     }
                   }
                 });
    x.resize(kept);
    y.resize(kept);
    z.resize(kept);
    index.resize(kept);
  }

 private:
  /// The inlier test over blocks of points: for each block, inside[j] = 1
  /// when |distance| <= threshold, else 0, then visit(base, count, inside,
  /// any_inside) (any_inside false: no inside[j] is 1).
  /// The test is the signed distance in double precision,
  /// (n_x x + n_y y) + n_z z - d as Eigen's n.dot(p) - d. It runs first in
  /// float (four points per SSE2 instruction, no data-dependent branch or
  /// store). The float distance differs from the double one by less than
  /// 8 * 2^-24 (|x| + |y| + |z| + |d|) (the rounding of n, d and five
  /// operations, each within 2^-24 of its operands' magnitude); `margin`,
  /// 1e-6 (3 max|coordinate| + |d| + threshold), bounds that and the
  /// rounding of the threshold itself. The float test decides every point
  /// farther than `margin` from the threshold; the few nearer are decided
  /// again in double. So the inliers are the double test's, exactly.
  template <typename Visit>
  void forEachBlock(const Eigen::Vector3d& n, double d, double threshold, Visit&& visit) const {
    constexpr std::size_t kBlock = 512;
    alignas(16) std::int32_t inside[kBlock];
    alignas(16) std::int32_t unsure[kBlock];
    const double margin =
        1e-6 * (3.0 * static_cast<double>(max_abs) + std::abs(d) + threshold) + 1e-12;
    const float nx = static_cast<float>(n.x()), ny = static_cast<float>(n.y()),
                nz = static_cast<float>(n.z()), df = static_cast<float>(d);
    const float inner = static_cast<float>(threshold - margin);
    const float outer = static_cast<float>(threshold + margin);
    const std::size_t count = x.size();
    for (std::size_t base = 0; base < count; base += kBlock) {
      const std::size_t m = std::min(kBlock, count - base);
      const float* __restrict px = x.data() + base;
      const float* __restrict py = y.data() + base;
      const float* __restrict pz = z.data() + base;
      std::int32_t any_unsure = 0, any_below_outer = 0;
      for (std::size_t j = 0; j < m; ++j) {
        const float distance = std::abs((nx * px[j] + ny * py[j]) + nz * pz[j] - df);
        const std::int32_t below_outer = distance <= outer ? 1 : 0;
        inside[j] = distance <= inner ? 1 : 0;
        unsure[j] = below_outer - inside[j];
        any_unsure |= unsure[j];
        any_below_outer |= below_outer;
      }
      if (any_unsure != 0) {
        for (std::size_t j = 0; j < m; ++j) {
          if (unsure[j] == 0) continue;
          const double distance =
              (n.x() * static_cast<double>(px[j]) + n.y() * static_cast<double>(py[j])) +
              n.z() * static_cast<double>(pz[j]) - d;
          inside[j] = std::abs(distance) <= threshold ? 1 : 0;
        }
      }
      visit(base, m, inside, any_below_outer != 0);
    }
  }
};

}  // namespace storey::backend
