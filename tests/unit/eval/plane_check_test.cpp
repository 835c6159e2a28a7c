// Plane associations checked with the true poses (`storey eval --planes`):
// a hand-made planes.json whose keyframes are placed by a known truth.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "eval/plane_check.h"
#include "support/temp_dir.h"

namespace storey::eval {
namespace {

/// One observation of the wall x = 3 (world) from a keyframe at (x, 0, 0)
/// with identity rotation: in the keyframe's frame the wall is x = 3 - x,
/// seen `shift` m farther than it is (a different surface when shift != 0).
nlohmann::json wallObservation(int keyframe, double x, double shift, bool outlier) {
  const double d = 3.0 - x + shift;
  return {{"keyframe", keyframe},      {"time", static_cast<double>(keyframe)},
          {"normal", {1.0, 0.0, 0.0}}, {"distance", d},
          {"centroid", {d, 0.5, 1.0}}, {"outlier", outlier}};
}

/// Keyframes k = 0..n-1 at time k, at (0.5 k, 0, 0) without rotation.
Trajectory truthAlongX(int n) {
  Trajectory gt;
  for (int k = 0; k < n; ++k)
    gt.push_back({static_cast<double>(k),
                  Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5 * k, 0, 0))});
  return gt;
}

TEST(PlaneCheck, FindsTheObservationOnAnotherSurface) {
  test::TempDir dir;
  const Trajectory gt = truthAlongX(5);
  nlohmann::json planes = {{"format", "storey planes, version 1"},
                           {"planes", nlohmann::json::array()}};
  nlohmann::json wall = {{"id", 7},
                         {"normal", {1.0, 0.0, 0.0}},
                         {"distance", 3.0},
                         {"observations", nlohmann::json::array()}};
  wall["observations"].push_back(wallObservation(0, 0.0, 0.0, false));
  wall["observations"].push_back(wallObservation(1, 0.5, 0.01, false));
  wall["observations"].push_back(wallObservation(2, 1.0, -0.01, true));  // right surface, flagged
  wall["observations"].push_back(wallObservation(3, 1.5, 0.30, false));  // 0.3 m off, survived
  wall["observations"].push_back(wallObservation(4, 2.0, -0.40, true));  // 0.4 m off, flagged
  planes["planes"].push_back(wall);
  const std::string path = dir.file("planes.json");
  std::ofstream(path) << planes.dump();

  const PlaneCheck check = checkPlanes(path, gt);
  EXPECT_EQ(check.planes, 1u);
  EXPECT_EQ(check.observations, 5u);
  EXPECT_EQ(check.down_weighted, 2u);
  ASSERT_EQ(check.wrong.size(), 2u);
  EXPECT_EQ(check.wrongNotDownWeighted(), 1u);
  EXPECT_EQ(check.wrong[0].keyframe, 3);
  EXPECT_NEAR(check.wrong[0].offset, 0.30, 1e-9);  // from the median offset (0)
  EXPECT_FALSE(check.wrong[0].down_weighted);
  EXPECT_EQ(check.wrong[1].keyframe, 4);
  EXPECT_TRUE(check.wrong[1].down_weighted);
  // |offsets| 0, 0.01, 0.01, 0.30, 0.40.
  EXPECT_NEAR(check.offset_median, 0.01, 1e-9);
  EXPECT_NEAR(check.offset_p90, 0.30, 1e-9);
  EXPECT_EQ(check.beyond_tight_offset, 2u);
}

TEST(PlaneCheck, ASurfaceAFewCentimetresOffIsCountedBeyondTheTightOffset) {
  // A door recess 5 cm behind the wall, merged into the wall's landmark:
  // not "off its plane" at 0.1 m, but beyond the 0.03 m tight offset.
  test::TempDir dir;
  const Trajectory gt = truthAlongX(10);
  nlohmann::json wall = {{"id", 3},
                         {"normal", {1.0, 0.0, 0.0}},
                         {"distance", 3.0},
                         {"observations", nlohmann::json::array()}};
  for (int k = 0; k < 10; ++k)
    wall["observations"].push_back(wallObservation(k, 0.5 * k, k >= 7 ? 0.05 : 0.0, false));
  const nlohmann::json planes = {{"format", "storey planes, version 1"}, {"planes", {wall}}};
  const std::string path = dir.file("planes.json");
  std::ofstream(path) << planes.dump();
  const PlaneCheck check = checkPlanes(path, gt);
  EXPECT_TRUE(check.wrong.empty());
  EXPECT_EQ(check.beyond_tight_offset, 3u);
  EXPECT_NEAR(check.offset_median, 0.0, 1e-9);
  EXPECT_NEAR(check.offset_p90, 0.05, 1e-9);
  EXPECT_DOUBLE_EQ(check.tight_offset, 0.03);
}

TEST(PlaneCheck, BadInputIsAClearError) {
  test::TempDir dir;
  const Trajectory gt{{0.0, Pose()}};
  EXPECT_THROW(checkPlanes(dir.file("missing.json"), gt), Error);
  std::ofstream(dir.file("bad.json")) << "{\"planes\": 3}";
  EXPECT_THROW(checkPlanes(dir.file("bad.json"), gt), Error);
  // An observation at a time the truth does not cover.
  nlohmann::json planes = {{"planes",
                            {{{"id", 0},
                              {"normal", {0, 0, 1}},
                              {"distance", 1.0},
                              {"observations", {wallObservation(0, 0.0, 0.0, false)}}}}}};
  planes["planes"][0]["observations"][0]["time"] = 99.0;
  std::ofstream(dir.file("late.json")) << planes.dump();
  try {
    checkPlanes(dir.file("late.json"), gt);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("plane 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace storey::eval
