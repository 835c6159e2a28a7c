#include "backend/srp_extraction.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "backend/plane_hull.h"
#include "backend/plane_math.h"
#include "backend/unexplained_points.h"
#include "types/voxel_hash.h"

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
                       const SrpExtractionConfig& config, int scan_points_per_inlier) {
  // One pass: sum of p and of p p^T (about the first point, for precision).
  DetectedPlane out;
  const double count = static_cast<double>(inliers.size());
  const Eigen::Vector3d o = inliers.front();
  // The six distinct entries of the symmetric sum (each the same products in
  // the same order as the full outer product's).
  double sx = 0.0, sy = 0.0, sz = 0.0, sxx = 0.0, sxy = 0.0, sxz = 0.0, syy = 0.0, syz = 0.0,
         szz = 0.0;
  for (const auto& p : inliers) {
    const double x = p.x() - o.x(), y = p.y() - o.y(), z = p.z() - o.z();
    sx += x;
    sy += y;
    sz += z;
    sxx += x * x;
    sxy += x * y;
    sxz += x * z;
    syy += y * y;
    syz += y * z;
    szz += z * z;
  }
  const Eigen::Vector3d sum(sx, sy, sz);
  Eigen::Matrix3d sum_sq;
  sum_sq << sxx, sxy, sxz, sxy, syy, syz, sxz, syz, szz;
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
  out.points = static_cast<int>(inliers.size()) * std::max(scan_points_per_inlier, 1);
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
  const double effective = std::min(static_cast<double>(out.points),
                                    static_cast<double>(std::max(config.max_effective_points, 3)));
  info *= effective / count / (sigma * sigma);
  out.covariance = info.inverse();
  return out;
}

namespace {

/// PCL's plane model with a faster inlier count. Debian's PCL is built for
/// the baseline x86-64 and counts with its "standard" loop, which builds an
/// Eigen::Vector4f per point on the stack and stalls on reading it back (half
/// of the extraction's time, measured with perf on bench_srp_extraction).
/// This count runs over a structure-of-arrays copy of the cloud and computes
/// exactly what that loop computes, in the same float operations and order:
/// s = (c0 x + c2 z) + (c1 y + c3) (Eigen's 4-float dot product),
/// counted when double(|s|) < threshold. So RANSAC (PCL's sampling and
/// stopping rule) finds the same planes, bit for bit, only sooner.
class PlaneModelFastCount : public pcl::SampleConsensusModelPlane<pcl::PointXYZ> {
 public:
  explicit PlaneModelFastCount(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud)
      : pcl::SampleConsensusModelPlane<pcl::PointXYZ>(cloud, false) {
    x_.reserve(cloud->size());
    y_.reserve(cloud->size());
    z_.reserve(cloud->size());
    for (const pcl::PointXYZ& p : *cloud) {
      x_.push_back(p.x);
      y_.push_back(p.y);
      z_.push_back(p.z);
    }
  }

  std::size_t countWithinDistance(const Eigen::VectorXf& coefficients,
                                  const double threshold) const override {
    if (!isModelValid(coefficients) || indices_->size() != x_.size()) {
      return pcl::SampleConsensusModelPlane<pcl::PointXYZ>::countWithinDistance(coefficients,
                                                                                threshold);
    }
    // double(f) < threshold  <=>  f < the smallest float not below threshold.
    float limit = static_cast<float>(threshold);
    if (static_cast<double>(limit) < threshold)
      limit = std::nextafter(limit, std::numeric_limits<float>::infinity());
    const float c0 = coefficients[0], c1 = coefficients[1], c2 = coefficients[2];
    const float c3 = coefficients[3];
    std::size_t count = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      const float s = (c0 * x_[i] + c2 * z_[i]) + (c1 * y_[i] + c3);
      count += std::abs(s) < limit ? 1 : 0;
    }
    return count;
  }

 private:
  std::vector<float> x_, y_, z_;
};

/// RANSAC plane (unit normal, d) on the unexplained subsample points; false when none.
bool ransacPlane(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& remaining,
                 const SrpExtractionConfig& config, Eigen::Vector3d& n, double& d) {
  // At most ransac_max_points hypotheses' support points, evenly strided.
  const std::size_t cap = static_cast<std::size_t>(std::max(config.ransac_max_points, 10));
  const double stride = remaining.size() > cap ? static_cast<double>(remaining.size()) / cap : 1.0;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(std::min(remaining.size(), cap) + 1);
  for (double k = 0.0; k < static_cast<double>(remaining.size()); k += stride) {
    const Eigen::Vector3f& p =
        points[static_cast<std::size_t>(remaining[static_cast<std::size_t>(k)])];
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  if (cloud->size() < 10) return false;
  // random = false: the model's generator has a fixed seed (deterministic output).
  pcl::SampleConsensusModelPlane<pcl::PointXYZ>::Ptr model(new PlaneModelFastCount(cloud));
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

/// Keeps the entries of `indices` whose point is not explained, in order.
void dropExplained(std::vector<int>& indices, const std::vector<char>& explained) {
  indices.erase(std::remove_if(indices.begin(), indices.end(),
                               [&](int i) { return explained[static_cast<std::size_t>(i)] != 0; }),
                indices.end());
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
  const double d = plane.plane.distance();
  if (d < 3.0 * ransac_distance) return true;
  // d < median(r) sin(a), with the median the element k = n / 2 of the
  // ranges in ascending order. d < fl(r sin(a)) holds for every range above
  // some value: it holds for the median when it holds for at least n - k
  // ranges, so a count decides it (no sort).
  const double sin_angle = std::sin(min_angle_deg * M_PI / 180.0);
  std::size_t holds = 0;
  for (const auto& p : inliers) holds += d < p.norm() * sin_angle ? 1 : 0;
  return holds >= inliers.size() - inliers.size() / 2;
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
  // A dense sensor's scan: one point of every k (scan order), so the cost
  // does not grow with the point count; a plane's fit counts at most
  // max_effective_points anyway. Each point kept stands for k scan points
  // (a plane's count, min_points and its uncertainty). The point kept of
  // each run of k is at a pseudo-random offset (a hash of the run's index):
  // a fixed one would keep the same few lasers of a multi-beam scan when k
  // divides their number.
  result.points = static_cast<int>(points.size());
  std::size_t stride = 1;
  const auto max_points = static_cast<std::size_t>(std::max(config.max_points, 0));
  if (max_points > 0 && points.size() > max_points) {
    stride = (points.size() + max_points - 1) / max_points;
    std::size_t kept = 0;
    for (std::size_t start = 0; start < points.size(); start += stride) {
      const std::size_t run = std::min(stride, points.size() - start);
      points[kept++] = points[start + voxelHash(start / stride) % run];
    }
    points.resize(kept);
  }
  if (points.size() * stride < static_cast<std::size_t>(std::max(config.min_points, 3)))
    return result;

  // Voxel subsample for the RANSAC hypotheses (first point of each voxel).
  // The unexplained points of the subsample and of the whole scan, in scan
  // order: a plane's inliers leave both lists once it is detected.
  std::vector<int> subsample;
  {
    VoxelIndex seen(points.size() / 4 + 16);
    const float inv = static_cast<float>(1.0 / config.voxel_size);
    bool inserted = false;
    std::uint64_t previous = ~std::uint64_t{0};  // no packed key (63 bits)
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3f& p = points[i];
      const std::uint64_t key = packVoxel(static_cast<std::int64_t>(std::floor(p.x() * inv)),
                                          static_cast<std::int64_t>(std::floor(p.y() * inv)),
                                          static_cast<std::int64_t>(std::floor(p.z() * inv)));
      // Neighbours in scan order often share a voxel: no lookup for those.
      if (key == previous) continue;
      previous = key;
      seen.findOrInsert(key, inserted);
      if (inserted) subsample.push_back(static_cast<int>(i));
    }
  }
  UnexplainedPoints unexplained(points);

  std::vector<char> explained(points.size(), 0);
  std::size_t explained_count = 0;
  const double target = config.explained_fraction * static_cast<double>(points.size());
  std::vector<DetectedPlane> accepted;
  std::vector<std::vector<Eigen::Vector3d>> accepted_inliers;
  std::vector<Eigen::Vector3d> inliers;
  std::vector<std::uint32_t> inlier_index;
  std::vector<std::uint32_t> within;
  for (int k = 0; k < config.max_detected_planes; ++k) {
    if (static_cast<double>(explained_count) >= target) break;
    Eigen::Vector3d n;
    double d = 0.0;
    if (!ransacPlane(points, subsample, config, n, d)) break;
    // Refine on the full-resolution points (two rounds of inliers + least squares).
    // The second round's inliers are the plane's points: they leave the
    // unexplained points in the same pass that finds them.
    DetectedPlane plane;
    for (int round = 0; round < 2; ++round) {
      if (round == 0) {
        unexplained.within(n, d, config.ransac_distance, within);
        inliers.clear();
        inlier_index.clear();
        for (std::uint32_t j : within) {
          // The coordinates already widened to double (exactly: float -> double).
          inliers.emplace_back(unexplained.x[j], unexplained.y[j], unexplained.z[j]);
          inlier_index.push_back(unexplained.index[j]);
        }
      } else {
        unexplained.extract(n, d, config.ransac_distance, inliers, inlier_index);
      }
      if (inliers.size() < 3) break;
      plane = fitPlane(inliers, config, static_cast<int>(stride));
      n = plane.plane.normal();
      d = plane.plane.distance();
    }
    if (inliers.size() < 3) break;
    for (std::size_t i : inlier_index) explained[i] = 1;
    explained_count += inlier_index.size();
    dropExplained(subsample, explained);
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
    accepted.push_back(plane);
    accepted_inliers.push_back(std::move(inliers));  // for the hull, if it becomes an SRP
    inliers = {};
  }
  result.explained_fraction =
      static_cast<double>(explained_count) / static_cast<double>(points.size());

  // The SRPs: the largest planes whose normals are nearly orthogonal to each
  // other; only they get their outline.
  std::vector<std::size_t> by_size(accepted.size());
  for (std::size_t i = 0; i < by_size.size(); ++i) by_size[i] = i;
  std::stable_sort(by_size.begin(), by_size.end(), [&](std::size_t a, std::size_t b) {
    return accepted[a].points > accepted[b].points;
  });
  const double max_dot = std::sin(config.orthogonal_tolerance_deg * M_PI / 180.0);
  for (std::size_t i : by_size) {
    DetectedPlane& plane = accepted[i];
    bool orthogonal = true;
    for (const DetectedPlane& srp : result.srps)
      if (std::abs(srp.plane.normal().dot(plane.plane.normal())) > max_dot) orthogonal = false;
    if (!orthogonal) {
      ++result.rejects[static_cast<int>(PlaneReject::kNotOrthogonal)];
    } else if (static_cast<int>(result.srps.size()) >= config.max_srps) {
      ++result.rejects[static_cast<int>(PlaneReject::kBeyondMaxSrps)];
    } else {
      plane.hull = planeHull(accepted_inliers[i], plane.plane);
      result.srps.push_back(std::move(plane));
    }
  }
  return result;
}

}  // namespace storey::backend
