#pragma once
/// LOAM-style feature extraction (Zhang & Singh, LOAM, RSS 2014), per ring:
/// a smoothness value from the 2k neighbours of each point along its ring,
/// sharp points (high value) as edge features, flat points (low value) as
/// planar features. Smoothness c = |sum_j (p_j - p_i)| / sum_j |p_j - p_i|
/// over the k neighbours on each side: 0 on a straight run of points, and
/// cos(phi / 2) at a crease of angle phi between the two sides (0.71 at a
/// right-angle corner), whatever the range and the angular resolution. Points whose neighbourhood
/// is unreliable are rejected and counted by reason: next to a gap in the ring (dropout, glass, max
/// range), on the far side of a depth discontinuity (occluded), or on a surface nearly parallel to
/// the beam.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "types/scan.h"

namespace storey {

class ParallelChunks;

struct FeatureConfig {
  int neighbours = 5;             ///< k points on each side along the ring [>= 2]
  int sectors = 6;                ///< each ring is split in this many sectors by time [>= 1]
  int max_edges_per_sector = 0;   ///< strongest edges kept per sector; 0: no edge features
                                  ///< (planar features only, as FAST-LIO2; odometry.md says why)
  double edge_threshold = 0.3;    ///< smoothness above which a point is an edge [-]
                                  ///< (0.3: creases sharper than about 145 deg)
  double plane_threshold = 0.1;   ///< smoothness below which a point is planar [-]
                                  ///< (0.1: flatter than about 168 deg)
  double occlusion_gap = 0.3;     ///< depth jump that marks an occlusion boundary [m]
  double parallel_ratio = 0.02;   ///< range step (fraction of range) to both neighbours that
                                  ///< marks a beam nearly parallel to the surface [-]
  double max_gap_factor = 3.0;    ///< a time step above this many median steps breaks the ring [-]
  double plane_voxel_size = 0.2;  ///< planar features are voxel-downsampled to this size [m]
  double edge_voxel_size = 0.1;   ///< edge features are voxel-downsampled to this size [m]
};

/// Why a point was not eligible as a feature (counts reported in the run report).
enum class FeatureReject : std::uint8_t {
  kRingGap = 0,   ///< fewer than k valid neighbours on a side (ring start/end, dropout)
  kOccluded,      ///< on the far side of a depth discontinuity
  kParallelBeam,  ///< surface nearly parallel to the beam
  kCount
};
const char* toString(FeatureReject reason);

struct FeatureSet {
  std::vector<Eigen::Vector3f> edges;   ///< edge features, LiDAR frame [m]
  std::vector<Eigen::Vector3f> planes;  ///< planar features, LiDAR frame [m]
  std::array<std::int64_t, static_cast<std::size_t>(FeatureReject::kCount)> rejected{};
  std::int64_t edge_candidates = 0;   ///< before non-maximum suppression and downsampling
  std::int64_t plane_candidates = 0;  ///< before downsampling
};

/// Extracts features from a (deskewed) scan. Points are grouped by ring and
/// ordered by their time along each ring.
/// With `parallel`, the rings are processed on its threads (the same result).
FeatureSet extractFeatures(const Scan& scan, const FeatureConfig& config,
                           const ParallelChunks* parallel = nullptr);

/// One point per occupied cube of side `voxel_size`: the point nearest to the
/// cube's centroid (voxel_size <= 0 returns the input). Deterministic order.
std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points,
                                             double voxel_size);

}  // namespace storey
