// SRP extraction on synthetic scans with known planes: the largest nearly
// orthogonal planes are found with their point counts and fit uncertainty;
// clutter (small, dense surfaces) and small scans give no SRP.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>

#include "backend/plane_math.h"
#include "backend/srp_extraction.h"

namespace storey::backend {
namespace {

struct Patch {
  Eigen::Vector3d origin, u, v;  // points origin + a u + b v, a, b in [0, 1]
  double spacing;
};

void addPatch(std::vector<Eigen::Vector3f>& points, const Patch& p, std::mt19937& rng,
              double noise) {
  std::normal_distribution<double> g(0.0, noise);
  const Eigen::Vector3d n = p.u.cross(p.v).normalized();
  const int nu = static_cast<int>(p.u.norm() / p.spacing),
            nv = static_cast<int>(p.v.norm() / p.spacing);
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const Eigen::Vector3d x =
          p.origin + p.u * (double(i) / nu) + p.v * (double(j) / nv) + n * g(rng);
      points.push_back(x.cast<float>());
    }
}

/// A room around the sensor: floor 0.6 m below, ceiling 2.4 m above, walls at
/// x = 4 and x = -3 (parallel), y = -2 and y = 2.5, a dense table top 0.3 m
/// below the sensor (clutter) and scattered points.
std::vector<Eigen::Vector3f> roomScan(std::mt19937& rng, bool with_clutter) {
  std::vector<Eigen::Vector3f> pts;
  const double noise = 0.01;
  addPatch(pts, {{-3, -2, -0.6}, {7, 0, 0}, {0, 4.5, 0}, 0.08}, rng, noise);    // floor (largest)
  addPatch(pts, {{-3, -2, 2.4}, {7, 0, 0}, {0, 4.5, 0}, 0.2}, rng, noise);      // ceiling (sparse)
  addPatch(pts, {{4, -2, -0.6}, {0, 4.5, 0}, {0, 0, 3.0}, 0.07}, rng, noise);   // wall x = 4
  addPatch(pts, {{-3, -2, -0.6}, {0, 4.5, 0}, {0, 0, 3.0}, 0.12}, rng, noise);  // wall x = -3
  addPatch(pts, {{-3, -2, -0.6}, {7, 0, 0}, {0, 0, 3.0}, 0.1}, rng, noise);     // wall y = -2
  addPatch(pts, {{-3, 2.5, -0.6}, {7, 0, 0}, {0, 0, 3.0}, 0.15}, rng, noise);   // wall y = 2.5
  if (with_clutter) {
    addPatch(pts, {{1.0, 0.5, -0.3}, {0.7, 0, 0}, {0, 0.5, 0}, 0.012}, rng, noise);  // table top
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    for (int i = 0; i < 1500; ++i) pts.push_back(Eigen::Vector3f(u(rng), u(rng), u(rng) * 0.5));
  }
  return pts;
}

bool near(const DetectedPlane& p, const Eigen::Vector3d& n, double d, double angle_deg,
          double dist) {
  return p.plane.normal().dot(n) > std::cos(angle_deg * M_PI / 180.0) &&
         std::abs(p.plane.distance() - d) < dist;
}

TEST(SrpExtraction, FindsTheLargestOrthogonalPlanesOfARoom) {
  std::mt19937 rng(1);
  const auto pts = roomScan(rng, true);
  SrpExtractionConfig config;
  const SrpExtractionResult r = extractSrps(pts, config);
  ASSERT_EQ(r.srps.size(), 3u);
  // Fixture property: the floor has the most points, then wall x = 4, then wall y = -2.
  EXPECT_TRUE(near(r.srps[0], {0, 0, -1}, 0.6, 0.5, 0.01));
  EXPECT_TRUE(near(r.srps[1], {1, 0, 0}, 4.0, 0.5, 0.01));
  EXPECT_TRUE(near(r.srps[2], {0, -1, 0}, 2.0, 0.5, 0.01));
  // The floor's outline (planes.json "hull") spans the 7 m x 4.5 m floor, on the plane.
  ASSERT_GE(r.srps[0].hull.size(), 4u);
  Eigen::Vector3d lo = r.srps[0].hull[0], hi = lo;
  for (const Eigen::Vector3d& v : r.srps[0].hull) {
    EXPECT_NEAR(r.srps[0].plane.signedDistance(v), 0.0, 1e-9);
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  EXPECT_NEAR(hi.x() - lo.x(), 7.0, 0.2);
  EXPECT_NEAR(hi.y() - lo.y(), 4.5, 0.2);
  for (const DetectedPlane& p : r.srps) {
    EXPECT_GE(p.points, config.min_points);
    EXPECT_LT(p.rms, 0.02);
    // Fit uncertainty: positive definite, normal std below 0.2 deg, distance std below 1 cm.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(p.covariance);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
    EXPECT_LT(std::sqrt(p.covariance(0, 0)), 0.2 * M_PI / 180.0);
    EXPECT_LT(std::sqrt(p.covariance(2, 2)), 0.01);
  }
  for (std::size_t i = 1; i < r.srps.size(); ++i) EXPECT_GE(r.srps[i - 1].points, r.srps[i].points);
  // The table top (d = 0.3, level) is never an SRP, and the parallel walls and
  // the ceiling were not taken beside the floor and the first walls.
  for (const DetectedPlane& p : r.srps) EXPECT_FALSE(near(p, {0, 0, -1}, 0.3, 5, 0.1));
  EXPECT_GE(r.rejects[static_cast<int>(PlaneReject::kNotOrthogonal)], 1);
}

TEST(SrpExtraction, DenseClutterIsTooSmall) {
  std::mt19937 rng(2);
  std::vector<Eigen::Vector3f> pts;
  // Only a dense 0.7 x 0.5 m table top (about 2400 points) and a small box side.
  addPatch(pts, {{1.0, 0.5, -0.3}, {0.7, 0, 0}, {0, 0.5, 0}, 0.012}, rng, 0.005);
  addPatch(pts, {{1.0, 0.5, -0.3}, {0, 0.5, 0}, {0, 0, 0.4}, 0.012}, rng, 0.005);
  ASSERT_GT(pts.size(), 2000u);  // fixture: far more points than min_points
  const SrpExtractionResult r = extractSrps(pts, SrpExtractionConfig{});
  EXPECT_TRUE(r.srps.empty());
  EXPECT_GE(r.rejects[static_cast<int>(PlaneReject::kTooSmall)], 1);
}

TEST(SrpExtraction, FewPointsGiveNoSrp) {
  std::mt19937 rng(4);
  std::vector<Eigen::Vector3f> pts;
  addPatch(pts, {{-3, -2, -0.6}, {7, 0, 0}, {0, 4.5, 0}, 0.5}, rng, 0.01);  // ~150 floor points
  EXPECT_TRUE(extractSrps(pts, SrpExtractionConfig{}).srps.empty());
}

TEST(SrpExtraction, IsDeterministic) {
  std::mt19937 rng(1);
  const auto pts = roomScan(rng, true);
  const SrpExtractionResult a = extractSrps(pts, SrpExtractionConfig{});
  const SrpExtractionResult b = extractSrps(pts, SrpExtractionConfig{});
  ASSERT_EQ(a.srps.size(), b.srps.size());
  for (std::size_t i = 0; i < a.srps.size(); ++i) {
    EXPECT_EQ(a.srps[i].points, b.srps[i].points);
    EXPECT_EQ(a.srps[i].plane.distance(), b.srps[i].plane.distance());
  }
}

// extraction.max_points: a dense scan is thinned to every k-th point; the
// planes come out the same to a fraction of the fit noise, each kept point
// standing for k scan points (the count, min_points and the uncertainty).
TEST(SrpExtraction, ADenseScanIsThinnedToTheSamePlanes) {
  std::mt19937 rng(1);
  const auto pts = roomScan(rng, true);
  SrpExtractionConfig all;
  all.max_points = 0;
  const SrpExtractionResult a = extractSrps(pts, all);  // a.points: those within range
  SrpExtractionConfig thinned;
  thinned.max_points = a.points / 3 + 1;  // every third point
  const SrpExtractionResult b = extractSrps(pts, thinned);
  EXPECT_EQ(b.points, a.points);
  ASSERT_EQ(a.srps.size(), 3u);
  ASSERT_EQ(b.srps.size(), a.srps.size());
  for (std::size_t i = 0; i < a.srps.size(); ++i) {
    EXPECT_GT(a.srps[i].plane.normal().dot(b.srps[i].plane.normal()), std::cos(0.1 * M_PI / 180.0));
    EXPECT_NEAR(a.srps[i].plane.distance(), b.srps[i].plane.distance(), 0.002);
    EXPECT_EQ(b.srps[i].points % 3, 0);
    EXPECT_NEAR(b.srps[i].points, a.srps[i].points, 0.1 * a.srps[i].points);
    // The same information (both beyond max_effective_points): the same
    // covariance up to the fits' own differences.
    EXPECT_NEAR(std::sqrt(b.srps[i].covariance(2, 2)), std::sqrt(a.srps[i].covariance(2, 2)),
                0.2 * std::sqrt(a.srps[i].covariance(2, 2)));
  }
}

TEST(SrpExtraction, AThinnedPlaneCountsTheScanPointsItStandsFor) {
  std::mt19937 rng(5);
  std::vector<Eigen::Vector3f> pts;
  addPatch(pts, {{-3, -2, -0.6}, {7, 0, 0}, {0, 4.5, 0}, 0.25}, rng, 0.01);  // ~560 floor points
  SrpExtractionConfig config;
  ASSERT_GT(pts.size(), static_cast<std::size_t>(config.min_points));  // fixture
  ASSERT_LT(pts.size(), 700u);
  config.max_points = 200;  // every third point: ~190 kept, fewer than min_points
  const SrpExtractionResult r = extractSrps(pts, config);
  ASSERT_EQ(r.srps.size(), 1u);
  EXPECT_NEAR(r.srps[0].points, static_cast<double>(pts.size()), 3.0);
  EXPECT_TRUE(near(r.srps[0], {0, 0, -1}, 0.6, 0.5, 0.01));
  // Thinned to fewer points than max_effective_points (every twelfth: ~47),
  // the plane keeps the information of the scan points it stands for.
  SrpExtractionConfig all = config, sparse = config;
  all.max_points = 0;
  sparse.max_points = 50;
  const SrpExtractionResult r_all = extractSrps(pts, all);
  const SrpExtractionResult r_sparse = extractSrps(pts, sparse);
  ASSERT_EQ(r_all.srps.size(), 1u);
  ASSERT_EQ(r_sparse.srps.size(), 1u);
  EXPECT_NEAR(r_sparse.srps[0].covariance(2, 2), r_all.srps[0].covariance(2, 2),
              0.35 * r_all.srps[0].covariance(2, 2));
}

// A multi-beam scan lists each column's lasers in turn: thinning to one
// point in k must not keep the same lasers of every column (with a fixed
// offset and k = 4, lasers 1, 5, ..., 29, which alone see the wall here,
// would all be dropped).
TEST(SrpExtraction, ThinningDoesNotKeepTheSameLasersOfEveryColumn) {
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<Eigen::Vector3f> pts;
  const int columns = 400, lasers = 32;
  for (int c = 0; c < columns; ++c) {
    const double along = -4.0 + 8.0 * c / columns;
    for (int l = 0; l < lasers; ++l) {
      if (l % 4 == 1) {  // the wall x = 5
        pts.emplace_back(static_cast<float>(5.0 + noise(rng)), static_cast<float>(along),
                         static_cast<float>(-1.0 + 3.0 * l / lasers));
      } else {  // the floor z = -1
        pts.emplace_back(static_cast<float>(along), static_cast<float>(-3.0 + 6.0 * l / lasers),
                         static_cast<float>(-1.0 + noise(rng)));
      }
    }
  }
  SrpExtractionConfig config;
  config.max_points = columns * lasers / 4;  // one point in four
  const SrpExtractionResult r = extractSrps(pts, config);
  const DetectedPlane* wall = nullptr;
  for (const DetectedPlane& p : r.srps)
    if (near(p, {1, 0, 0}, 5.0, 1.0, 0.02)) wall = &p;
  ASSERT_NE(wall, nullptr) << r.srps.size() << " SRPs, none the wall";
  EXPECT_NEAR(wall->points, columns * lasers / 4, 0.15 * columns * lasers / 4);
}

TEST(FitPlane, RecoversAKnownPlaneAndItsUncertaintyShrinksWithExtent) {
  std::mt19937 rng(9);
  std::normal_distribution<double> g(0.0, 0.02);
  SrpExtractionConfig config;
  auto make = [&](double size) {
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < 400; ++i) {
      const double a = size * (i % 20) / 19.0, b = size * (i / 20) / 19.0;
      pts.push_back(Eigen::Vector3d(a, b, 0.0) + Eigen::Vector3d(0, 0, -1.5 + g(rng)));
    }
    return fitPlane(pts, config);
  };
  const DetectedPlane small = make(1.0), large = make(4.0);
  EXPECT_NEAR(small.plane.distance(), 1.5, 0.01);
  EXPECT_GT(small.plane.normal().dot(Eigen::Vector3d(0, 0, -1)), std::cos(1.0 * M_PI / 180));
  EXPECT_GT(small.covariance(0, 0), 4.0 * large.covariance(0, 0));
}

/// A VLP-16-like scan (16 rings, -15 to +15 deg, 0.2 deg azimuth steps) in a
/// round shaft of radius 1.2 m (no wall is a plane; the floor is out of the
/// beams' reach): the +-1 deg rings trace z = +-2.1 cm on the wall, 3600
/// points within the RANSAC distance of the horizontal plane through the
/// sensor, spread over the whole circle.
std::vector<Eigen::Vector3f> roundRoomRings() {
  std::vector<Eigen::Vector3f> pts;
  for (int ring = 0; ring < 16; ++ring) {
    const double el = (-15.0 + 2.0 * ring) * M_PI / 180.0;
    for (int k = 0; k < 1800; ++k) {
      const double az = k * 0.2 * M_PI / 180.0;
      const Eigen::Vector3d dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                std::sin(el));
      pts.push_back((dir * (1.2 / std::cos(el))).cast<float>());
    }
  }
  return pts;
}

TEST(SrpExtraction, TheSensorsOwnBeamConeIsNoPlane) {
  const auto pts = roundRoomRings();
  auto throughSensor = [](const SrpExtractionResult& r) {
    for (const DetectedPlane& p : r.srps)
      if (p.plane.distance() < 0.1) return true;
    return false;
  };
  // Fixture check: without the view-angle test, the +-1 deg rings make a
  // horizontal "plane" through the sensor that passes the point count and
  // the extent.
  SrpExtractionConfig no_check;
  no_check.min_view_angle_deg = 0.0;
  ASSERT_TRUE(throughSensor(extractSrps(pts, no_check)));

  const SrpExtractionResult r = extractSrps(pts, SrpExtractionConfig{});
  EXPECT_FALSE(throughSensor(r));
  EXPECT_GE(r.rejects[static_cast<int>(PlaneReject::kEdgeOn)], 1);
}

}  // namespace
}  // namespace storey::backend

namespace storey::backend {
namespace {

// seenEdgeOn decides "d < median(range) sin(angle)" by counting; it must agree
// with the median taken as the middle element (n / 2 of the sorted ranges),
// for odd and even counts and with ranges exactly at the decision value.
TEST(SeenEdgeOn, AgreesWithTheMedianOfTheRanges) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> range(10.0, 60.0);  // decision values > 3 x 0.05 m
  std::uniform_real_distribution<double> direction(-1.0, 1.0);
  const double angle_deg = 1.0;
  const double sin_angle = std::sin(angle_deg * M_PI / 180.0);
  int edge_on = 0, checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const std::size_t n = 1 + static_cast<std::size_t>(trial % 40);
    std::vector<Eigen::Vector3d> inliers;
    std::vector<double> ranges;
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d u =
          Eigen::Vector3d(direction(rng), direction(rng), direction(rng) + 2.0).normalized();
      inliers.push_back(range(rng) * u);
      ranges.push_back(inliers.back().norm());
    }
    std::vector<double> sorted = ranges;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2),
                     sorted.end());
    const double median = sorted[n / 2];
    // Planes at distances around the decision value: below, at and above it,
    // and at the value some other range gives.
    const double other = ranges[static_cast<std::size_t>(trial) % n] * sin_angle;
    for (double d : {median * sin_angle, std::nextafter(median * sin_angle, 0.0),
                     std::nextafter(median * sin_angle, 1e9), other, 0.5 * median * sin_angle}) {
      DetectedPlane plane;
      plane.plane = Plane(Eigen::Vector3d::UnitZ(), d);
      const bool expected = d < median * sin_angle;
      EXPECT_EQ(seenEdgeOn(plane, inliers, angle_deg, 0.05), expected)
          << "n " << n << " d " << d << " median " << median;
      edge_on += expected ? 1 : 0;
      ++checked;
    }
  }
  // Both outcomes occur.
  EXPECT_GT(edge_on, checked / 10);
  EXPECT_LT(edge_on, checked - checked / 10);
}

}  // namespace
}  // namespace storey::backend
