#pragma once
/// Structural representative planes (SRP) of one keyframe scan (section V-A of
/// the reference paper): planes are detected with RANSAC one after the other
/// (the largest first) until a share of the points is explained; planes with
/// too few points or too small an extent (clutter) are not kept; of the rest,
/// the (up to) three with the most points whose normals are nearly orthogonal
/// are the SRPs. Each carries its point count and the covariance of its fit.
#include <Eigen/Core>
#include <vector>

#include "backend/backend_config.h"
#include "types/plane.h"

namespace storey::backend {

/// A plane found in a scan, in the scan's (keyframe's LiDAR) frame.
struct DetectedPlane {
  Plane plane;          ///< Hesse form, d >= 0: the sensor is on the side opposite n
  int points = 0;       ///< scan points within ransac_distance of the plane
  double rms = 0.0;     ///< RMS point-to-plane distance of those points [m]
  double extent = 0.0;  ///< 4 std of the inliers along their second axis [m]
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< of the inliers [m]
  /// Outline: convex hull of the inliers on the plane (backend/plane_hull.h);
  /// filled for the SRPs [m].
  std::vector<Eigen::Vector3d> hull;
  /// Covariance of (a1, a2, d): n' = normalise(n + B (a1, a2)), d' = d + dd, with
  /// B = tangentBasis(n) [rad^2, rad m, m^2].
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

/// Why a detected plane did not become an SRP.
enum class PlaneReject {
  kTooFewPoints,
  kTooSmall,
  kEdgeOn,
  kNotOrthogonal,
  kBeyondMaxSrps,
  kCount
};
const char* toString(PlaneReject reason);

struct SrpExtractionResult {
  std::vector<DetectedPlane> srps;      ///< at most max_srps, most points first
  std::vector<DetectedPlane> detected;  ///< every plane RANSAC found (SRPs included)
  int points = 0;                       ///< scan points within the range limits
  double explained_fraction = 0.0;      ///< share of those in a detected plane [0, 1]
  int rejects[static_cast<int>(PlaneReject::kCount)] = {};
};

/// Runs the extraction on points in the scan's frame (sensor at the origin).
/// Deterministic: the same points give the same planes.
SrpExtractionResult extractSrps(const std::vector<Eigen::Vector3f>& points,
                                const SrpExtractionConfig& config);

/// Fits a plane to points by least squares (PCA) and fills points, rms,
/// extent, centroid and covariance (point noise max(rms, point_sigma), at most
/// max_effective_points counted as independent). Needs >= 3 points. Each
/// inlier stands for `scan_points_per_inlier` scan points (a thinned scan,
/// extraction.max_points): `points` counts those, and so does the
/// uncertainty.
DetectedPlane fitPlane(const std::vector<Eigen::Vector3d>& inliers,
                       const SrpExtractionConfig& config, int scan_points_per_inlier = 1);

/// True when `plane` (with its `inliers`, sensor frame) is the sensor's own
/// beam cone: within 3 ransac_distance of the sensor, or the median beam
/// angle to it, asin(d / median range), below min_angle_deg (<= 0: never).
bool seenEdgeOn(const DetectedPlane& plane, const std::vector<Eigen::Vector3d>& inliers,
                double min_angle_deg, double ransac_distance);

}  // namespace storey::backend
