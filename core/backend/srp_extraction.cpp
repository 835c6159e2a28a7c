#include "backend/srp_extraction.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "backend/plane_hull.h"
#include "backend/plane_math.h"

namespace storey::backend {

const char* toString(PlaneReject reason) {
  switch (reason) {
    case PlaneReject::kTooFewPoints:
      return "too_few_points";
    case PlaneReject::kTooSmall:
      return "too_small_extent";
    case PlaneReject::kEdgeOn:
      return "seen_edge_on";
    case PlaneReject::kNotOrthogonal:
      return "not_orthogonal_to_larger_planes";
    case PlaneReject::kBeyondMaxSrps:
      return "beyond_max_srps";
    case PlaneReject::kCount:
      break;
  }
  return "unknown";
}

DetectedPlane fitPlane(const std::vector<Eigen::Vector3d>& inliers,
                       const SrpExtractionConfig& config) {
  // One pass: sum of p and of p p^T (about the first point, for precision).
  DetectedPlane out;
  const double count = static_cast<double>(inliers.size());
  const Eigen::Vector3d o = inliers.front();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
  for (const auto& p : inliers) {
    const Eigen::Vector3d q = p - o;
    sum += q;
    sum_sq.noalias() += q * q.transpose();
  }
  const Eigen::Vector3d mean_q = sum / count;
  const Eigen::Matrix3d cov = sum_sq / count - mean_q * mean_q.transpose();
  const Eigen::Vector3d c = o + mean_q;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // ascending eigenvalues
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  double d = n.dot(c);
  if (d < 0) {
    n = -n;
    d = -d;
  }
  out.plane = Plane(n, d);
  out.points = static_cast<int>(inliers.size());
  out.rms = std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
  out.extent = 4.0 * std::sqrt(std::max(0.0, eig.eigenvalues()(1)));
  out.centroid = c;

  // Information of (a1, a2, dd) from r_i = (n + B a) . p_i - (d + dd): J_i = [p_i^T B, -1],
  // so sum J_i J_i^T = [B^T S B, -B^T s; -s^T B, N] with S = sum p p^T, s = sum p;
  // the points count as at most max_effective_points independent ones.
  const Eigen::Matrix<double, 3, 2> B = tangentBasis(out.plane.normal());
  const Eigen::Matrix3d S = count * (cov + c * c.transpose());
  const Eigen::Vector3d s = count * c;
  Eigen::Matrix3d info;
  info.topLeftCorner<2, 2>() = B.transpose() * S * B;
  info.topRightCorner<2, 1>() = -B.transpose() * s;
  info.bottomLeftCorner<1, 2>() = info.topRightCorner<2, 1>().transpose();
  info(2, 2) = count;
  const double sigma = std::max(out.rms, config.point_sigma);
  const double effective =
      std::min(count, static_cast<double>(std::max(config.max_effective_points, 3)));
  info *= effective / count / (sigma * sigma);
  out.covariance = info.inverse();
  return out;
}

namespace {

std::int64_t voxelKey(const Eigen::Vector3f& p, float inv) {
  const auto ix = static_cast<std::int64_t>(std::floor(p.x() * inv)) + (1 << 20);
  const auto iy = static_cast<std::int64_t>(std::floor(p.y() * inv)) + (1 << 20);
  const auto iz = static_cast<std::int64_t>(std::floor(p.z() * inv)) + (1 << 20);
  return (ix << 42) | (iy << 21) | iz;
}

/// RANSAC plane (unit normal, d) on the remaining subsample; false when none.
bool ransacPlane(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& subsample,
                 const std::vector<char>& explained, const SrpExtractionConfig& config,
                 Eigen::Vector3d& n, double& d) {
  std::vector<int> remaining;
  remaining.reserve(subsample.size());
  for (int i : subsample)
    if (!explained[static_cast<std::size_t>(i)]) remaining.push_back(i);
  // At most ransac_max_points hypotheses' support points, evenly strided.
  const std::size_t cap = static_cast<std::size_t>(std::max(config.ransac_max_points, 10));
  const double stride = remaining.size() > cap ? static_cast<double>(remaining.size()) / cap : 1.0;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(std::min(remaining.size(), cap));
  for (double k = 0.0; k < static_cast<double>(remaining.size()); k += stride) {
    const Eigen::Vector3f& p =
        points[static_cast<std::size_t>(remaining[static_cast<std::size_t>(k)])];
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  if (cloud->size() < 10) return false;
  // random = false: the model's generator has a fixed seed (deterministic output).
  pcl::SampleConsensusModelPlane<pcl::PointXYZ>::Ptr model(
      new pcl::SampleConsensusModelPlane<pcl::PointXYZ>(cloud, false));
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, config.ransac_distance);
  ransac.setMaxIterations(config.ransac_iterations);
  ransac.setProbability(0.99);
  if (!ransac.computeModel()) return false;
  Eigen::VectorXf coefficients;
  ransac.getModelCoefficients(coefficients);
  if (coefficients.size() != 4) return false;
  Eigen::Vector3d normal(coefficients[0], coefficients[1], coefficients[2]);
  const double norm = normal.norm();
  if (!(norm > 1e-9)) return false;
  n = normal / norm;
  d = -static_cast<double>(coefficients[3]) / norm;
  return true;
}

}  // namespace

/// A plane at distance d from the sensor is seen under the angle asin(d / r)
/// at range r. The near-horizontal beams (+-1 deg, +-3 deg of a VLP-16)
/// trace flat cones on the walls around the sensor, and within the RANSAC
/// distance their points look like a large plane through (or within a
/// RANSAC band of) the sensor. Such a "plane" is seen edge-on: it passes
/// within three RANSAC distances of the sensor, or the median of the angle
/// over its inliers is below `min_angle_deg` (a farther, larger cone). A
/// real surface is not seen edge-on from everywhere.
bool seenEdgeOn(const DetectedPlane& plane, const std::vector<Eigen::Vector3d>& inliers,
                double min_angle_deg, double ransac_distance) {
  if (min_angle_deg <= 0.0 || inliers.empty()) return false;
  if (plane.plane.distance() < 3.0 * ransac_distance) return true;
  std::vector<double> ranges;
  ranges.reserve(inliers.size());
  for (const auto& p : inliers) ranges.push_back(p.norm());
  auto middle = ranges.begin() + static_cast<std::ptrdiff_t>(ranges.size() / 2);
  std::nth_element(ranges.begin(), middle, ranges.end());
  return plane.plane.distance() < *middle * std::sin(min_angle_deg * M_PI / 180.0);
}

SrpExtractionResult extractSrps(const std::vector<Eigen::Vector3f>& all_points,
                                const SrpExtractionConfig& config) {
  SrpExtractionResult result;
  std::vector<Eigen::Vector3f> points;
  points.reserve(all_points.size());
  const double min_r2 = config.min_range * config.min_range;
  const double max_r2 = config.max_range * config.max_range;
  for (const auto& p : all_points) {
    const double r2 = p.cast<double>().squaredNorm();
    if (std::isfinite(r2) && r2 >= min_r2 && r2 <= max_r2) points.push_back(p);
  }
  result.points = static_cast<int>(points.size());
  if (points.size() < static_cast<std::size_t>(std::max(config.min_points, 3))) return result;

  // Voxel subsample for the RANSAC hypotheses (first point of each voxel).
  std::vector<int> subsample;
  {
    std::unordered_set<std::int64_t> seen;
    seen.reserve(points.size());
    const float inv = static_cast<float>(1.0 / config.voxel_size);
    for (std::size_t i = 0; i < points.size(); ++i)
      if (seen.insert(voxelKey(points[i], inv)).second) subsample.push_back(static_cast<int>(i));
  }

  std::vector<char> explained(points.size(), 0);
  std::size_t explained_count = 0;
  const double target = config.explained_fraction * static_cast<double>(points.size());
  std::vector<DetectedPlane> accepted;
  std::vector<Eigen::Vector3d> inliers;
  std::vector<std::size_t> inlier_index;
  for (int k = 0; k < config.max_detected_planes; ++k) {
    if (static_cast<double>(explained_count) >= target) break;
    Eigen::Vector3d n;
    double d = 0.0;
    if (!ransacPlane(points, subsample, explained, config, n, d)) break;
    // Refine on the full-resolution points (two rounds of inliers + least squares).
    DetectedPlane plane;
    for (int round = 0; round < 2; ++round) {
      inliers.clear();
      inlier_index.clear();
      for (std::size_t i = 0; i < points.size(); ++i) {
        if (explained[i]) continue;
        const Eigen::Vector3d p = points[i].cast<double>();
        if (std::abs(n.dot(p) - d) <= config.ransac_distance) {
          inliers.push_back(p);
          inlier_index.push_back(i);
        }
      }
      if (inliers.size() < 3) break;
      plane = fitPlane(inliers, config);
      n = plane.plane.normal();
      d = plane.plane.distance();
    }
    if (inliers.size() < 3) break;
    for (std::size_t i : inlier_index) explained[i] = 1;
    explained_count += inlier_index.size();
    result.detected.push_back(plane);
    if (plane.points < config.min_points) {
      ++result.rejects[static_cast<int>(PlaneReject::kTooFewPoints)];
      // RANSAC takes the largest plane first: what remains is smaller still.
      if (plane.points < config.min_points / 2) break;
      continue;
    }
    if (plane.extent < config.min_extent) {
      ++result.rejects[static_cast<int>(PlaneReject::kTooSmall)];
      continue;
    }
    if (seenEdgeOn(plane, inliers, config.min_view_angle_deg, config.ransac_distance)) {
      ++result.rejects[static_cast<int>(PlaneReject::kEdgeOn)];
      continue;
    }
    plane.hull = planeHull(inliers, plane.plane);
    accepted.push_back(plane);
  }
  result.explained_fraction =
      static_cast<double>(explained_count) / static_cast<double>(points.size());

  // The SRPs: the largest planes whose normals are nearly orthogonal to each other.
  std::stable_sort(
      accepted.begin(), accepted.end(),
      [](const DetectedPlane& a, const DetectedPlane& b) { return a.points > b.points; });
  const double max_dot = std::sin(config.orthogonal_tolerance_deg * M_PI / 180.0);
  for (const DetectedPlane& plane : accepted) {
    bool orthogonal = true;
    for (const DetectedPlane& srp : result.srps)
      if (std::abs(srp.plane.normal().dot(plane.plane.normal())) > max_dot) orthogonal = false;
    if (!orthogonal) {
      ++result.rejects[static_cast<int>(PlaneReject::kNotOrthogonal)];
    } else if (static_cast<int>(result.srps.size()) >= config.max_srps) {
      ++result.rejects[static_cast<int>(PlaneReject::kBeyondMaxSrps)];
    } else {
      result.srps.push_back(plane);
    }
  }
  return result;
}

}  // namespace storey::backend
