// LiDAR-only scan registration on the real fast_gicp HDL-32E pair, against
// the reference relative transform shipped with it.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/pcd_file.h"
#include "odometry/scan_registration.h"
#include "odometry/voxel_map.h"
#include "real_data.h"

namespace storey {
namespace {

std::vector<Eigen::Vector3f> xyzOf(const PcdCloud& cloud) {
  std::vector<Eigen::Vector3f> out;
  const auto& h = cloud.header;
  std::uint32_t ox = 0, oy = 0, oz = 0;
  for (const auto& f : h.fields) {
    if (f.name == "x") ox = f.offset;
    if (f.name == "y") oy = f.offset;
    if (f.name == "z") oz = f.offset;
  }
  for (std::uint64_t i = 0; i < h.points; ++i) {
    float x, y, z;
    const std::uint8_t* p = cloud.bytes.data() + i * h.point_step;
    std::memcpy(&x, p + ox, 4);
    std::memcpy(&y, p + oy, 4);
    std::memcpy(&z, p + oz, 4);
    out.emplace_back(x, y, z);
  }
  return out;
}

/// Median distance of the source points, mapped by T, to their nearest target point [m].
double medianResidual(const std::vector<Eigen::Vector3f>& source, const std::vector<Eigen::Vector3f>& target,
                      const Pose& T) {
  VoxelMap map(VoxelMapConfig{1.0, 100000, 0.0, 1e9});
  std::vector<Eigen::Vector3f> finite;
  for (const auto& p : target) {
    if (p.allFinite() && p.norm() > 0.3) finite.push_back(p);
  }
  map.insert(finite);
  std::vector<double> d;
  for (const auto& p : source) {
    if (!p.allFinite() || p.norm() <= 0.3) continue;
    const Eigen::Vector3f q = (T * p.cast<double>()).cast<float>();
    const auto nn = map.nearest(q, 1, 1.0f);
    if (!nn.empty()) d.push_back((nn[0] - q).norm());
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

TEST(ScanRegistration, RecoversTheFastGicpReferenceTransform) {
  const std::string dir = test::realData("fast_gicp-scan-pair");
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "real data absent: " << dir;
  const auto target = xyzOf(readPcd(dir + "/251370668.pcd"));
  const auto source = xyzOf(readPcd(dir + "/251371071.pcd"));
  ASSERT_EQ(target.size(), 69088u);
  ASSERT_EQ(source.size(), 69792u);
  Eigen::Matrix4d reference;
  std::ifstream in(dir + "/relative.txt");
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) in >> reference(r, c);
  }
  ASSERT_TRUE(in);
  const Pose T_ref(Eigen::Matrix3d(reference.block<3, 3>(0, 0)), reference.block<3, 1>(0, 3));
  // The fixture is not trivial: half a metre and half a degree apart.
  ASSERT_GT(T_ref.translation().norm(), 0.4);

  const ScanRegistrationResult result = registerScan(source, target, Pose());
  const Pose error = T_ref.inverse() * result.T_target_source;
  const double rotation_error_deg = Eigen::AngleAxisd(error.rotation()).angle() * 180.0 / M_PI;
  const double translation_error_m = error.translation().norm();
  // The reference is itself an estimate: compare the fit too (median distance
  // of the mapped source points to their nearest target point).
  const double residual_identity = medianResidual(source, target, Pose());
  const double residual_reference = medianResidual(source, target, T_ref);
  const double residual_ours = medianResidual(source, target, result.T_target_source);
  std::printf("[ registration ] median nearest-neighbour residual: identity %.4f m, reference %.4f m, ours %.4f m\n",
              residual_identity, residual_reference, residual_ours);
  EXPECT_LT(residual_ours, residual_reference + 0.002);
  std::printf("[ registration ] %d rounds, %d matches of %d points, rms %.4f m, converged %d: "
              "rotation error %.4f deg, translation error %.4f m\n",
              result.rounds, result.matches, result.source_points, result.rms_distance,
              result.converged, rotation_error_deg, translation_error_m);
  EXPECT_TRUE(result.converged);
  EXPECT_LT(rotation_error_deg, 0.15);
  EXPECT_LT(translation_error_m, 0.025);
}

}  // namespace
}  // namespace storey
