// The plugin's logic that needs neither Qt nor CloudCompare: the rectangle
// shown for each SRP, the calibration/output defaults and the console's lines
// after a run. (planes.json itself
// is tested in tests/unit/export/planes_json_test.cpp, "Export storeys"'
// writer core/export/storey_files.h in tests/unit/export/storey_files_test.cpp.)
// Expected values are worked out by hand from the fixtures below.
#include <gtest/gtest.h>

#include <filesystem>

#include "PlanePatch.h"
#include "StoreyRun.h"
#include "common/error.h"
#include "export/planes_json.h"
#include "support/temp_dir.h"

namespace storey::plugin {
namespace {

// A wall x = 2 (n = +x, d = 2) seen from two keyframes: keyframe 0 at the
// origin, keyframe 1 moved by +1 m in y and turned 90 deg about z, so its
// LiDAR frame sees the wall at y_lidar = -2 ... and the hull below.
const char* kPlanes = R"({
  "format": "storey planes, version 1",
  "planes": [
    {"id": 0, "normal": [1, 0, 0], "distance": 2.0, "observations": [
      {"keyframe": 0, "normal": [1, 0, 0], "distance": 2.0, "points": 500,
       "hull": [[2, 0, 0], [2, 3, 0], [2, 3, 2.5], [2, 0, 2.5]]},
      {"keyframe": 1, "normal": [0, -1, 0], "distance": 2.0, "points": 400,
       "hull": [[-1, -2, 0], [3, -2, 0], [3, -2, 1]]}
    ]},
    {"id": 1, "normal": [0, 0, 1], "distance": 0.0, "facing": [0, 0, 1], "observations": [
      {"keyframe": 0, "normal": [0, 0, -1], "distance": 1.0, "points": 900}
    ]},
    {"id": 2, "normal": [0, 0, 1], "distance": 2.5, "observations": [
      {"keyframe": 0, "normal": [0, 0, 1], "distance": 2.5, "points": 700}
    ]}
  ]
})";

Trajectory twoKeyframes() {
  Trajectory t(2);
  t[0].time = 0.0;
  t[1].time = 1.0;
  // R_z(+90 deg): x_lidar -> y_world, y_lidar -> -x_world.
  t[1].pose = Pose(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())),
                   Eigen::Vector3d(0, 1, 0));
  return t;
}

std::vector<GlobalPlane> fixturePlanes() {
  return parsePlanesJson(kPlanes, "kPlanes").planes;
}

TEST(PluginPlanes, PatchCoversTheHullsOfEveryKeyframe) {
  const std::vector<GlobalPlane> planes = fixturePlanes();
  const PlanePatch patch = planePatch(planes[0], twoKeyframes());
  // Keyframe 1's hull in the world: (-1,-2,0) -> (2, 0, 0), (3,-2,0) -> (2, 4, 0),
  // (3,-2,1) -> (2, 4, 1). Union with keyframe 0's: y in [0, 4], z in [0, 2.5].
  EXPECT_TRUE(patch.from_hulls);
  EXPECT_NEAR(patch.width, 4.0, 1e-9);   // horizontal (u) for a wall
  EXPECT_NEAR(patch.height, 2.5, 1e-9);  // vertical (v)
  EXPECT_NEAR((patch.center - Eigen::Vector3d(2, 2, 1.25)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(patch.u.z(), 0.0, 1e-12);
  EXPECT_NEAR(patch.u.cross(patch.v).dot(patch.normal), 1.0, 1e-12);  // right-handed
  EXPECT_TRUE(onPatch(patch, {2.03, 3.9, 2.4}, 0.05, 0.0));
  EXPECT_FALSE(onPatch(patch, {2.10, 3.9, 2.4}, 0.05, 0.0));  // off the plane
  EXPECT_FALSE(onPatch(patch, {2.0, 4.5, 1.0}, 0.05, 0.1));   // beyond its edge
}

TEST(PluginPlanes, WithoutHullsAFixedSquareAtTheObservation) {
  const std::vector<GlobalPlane> planes = fixturePlanes();
  // Floor seen 1 m below keyframe 0 (at the origin): foot of the perpendicular
  // (0, 0, -1), projected onto the global plane z = 0 -> centre (0, 0, 0).
  const PlanePatch patch = planePatch(planes[1], twoKeyframes(), 3.0);
  EXPECT_FALSE(patch.from_hulls);
  EXPECT_DOUBLE_EQ(patch.width, 3.0);
  EXPECT_DOUBLE_EQ(patch.height, 3.0);
  EXPECT_NEAR(patch.center.norm(), 0.0, 1e-12);
}

TEST(PluginPlanes, KindFromNormalAndTheSideItWasSeenFrom) {
  const std::vector<GlobalPlane> planes = fixturePlanes();
  EXPECT_EQ(planeKind(planes[0], twoKeyframes()), "wall");
  EXPECT_EQ(planeKind(planes[1], twoKeyframes()), "floor");  // from "facing"
  // No "facing": z = 2.5 observed by a sensor at z = 0, so from below.
  EXPECT_FALSE(planes[2].facing_world);
  EXPECT_EQ(planeKind(planes[2], twoKeyframes()), "ceiling");
  GlobalPlane slanted = planes[0];
  slanted.normal_world = Eigen::Vector3d(1, 0, 1).normalized();  // 45 deg
  EXPECT_EQ(planeKind(slanted, twoKeyframes()), "plane");
}

TEST(PluginRun, CalibrationBesideTheLogAndDefaultOutputFolder) {
  test::TempDir dir;
  const std::string log = dir.write("walk.bag", "x");
  RunRequest r;
  r.log_path = log;
  EXPECT_EQ(resolveCalibration(r), "");
  const std::string calibration = dir.write("calibration.yaml", "x");
  EXPECT_EQ(resolveCalibration(r), calibration);
  r.calibration_path = "/elsewhere/cal.yaml";
  EXPECT_EQ(resolveCalibration(r), "/elsewhere/cal.yaml");
  EXPECT_EQ(resolveOutDir(r), dir.file("walk_storey"));
  r.out_dir = "/tmp/o";
  EXPECT_EQ(resolveOutDir(r), "/tmp/o");
}

TEST(PluginRun, AFoldersCalibrationInsideOrBesideIt) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.file("walk_ros2"));
  RunRequest r;
  r.log_path = dir.file("walk_ros2");
  EXPECT_EQ(resolveCalibration(r), "");
  const std::string beside = dir.write("calibration.yaml", "x");  // storey simulate --ros2
  EXPECT_EQ(resolveCalibration(r), beside);
  r.log_path += "/";
  EXPECT_EQ(resolveCalibration(r), beside);
  const std::string inside = dir.write("walk_ros2/calibration.yaml", "x");  // a PCD folder's
  EXPECT_EQ(resolveCalibration(r), inside);
}

TEST(PluginRun, MissingLogIsAnErrorNamingIt) {
  RunRequest r;
  r.log_path = "/nonexistent/walk.bag";
  try {
    runStorey(r, Config{}, nullptr);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/walk.bag"), std::string::npos) << e.what();
  }
}

TEST(PluginRun, ConsoleLinesAreTheRunSummaryAndItsWarnings) {
  RunOutcome o;
  o.out_dir = "/runs/walk_storey";
  o.seconds = 12.34;
  o.result.report_json = R"({"input": {"log": "/runs/walk.bag"},
    "map": {"points": 1000, "voxel_size_m": 0.02},
    "storeys": [{"index": 0, "floor_elevation": 0.0, "clear_height": 2.5, "area": 30}],
    "warning_count": 2, "warnings": ["IMU gap of 0.2 s", "scan dropped"]})";
  const std::vector<ConsoleLine> lines = runConsoleLines(o, "3 SRPs");
  ASSERT_GE(lines.size(), 4u);
  EXPECT_EQ(lines[0].text, "[Storey] done in 12.3 s: 3 SRPs");
  auto has = [&lines](const std::string& text, bool warning) {
    for (const ConsoleLine& l : lines)
      if (l.text == text) return l.warning == warning;
    return false;
  };
  EXPECT_TRUE(has("[Storey]   log: /runs/walk.bag", false));
  EXPECT_TRUE(has("[Storey]     storey 0: floor at 0.00 m, clear height 2.50 m, 30 m^2", false));
  EXPECT_TRUE(has("[Storey]   warnings: 2 (report.md)", false));
  EXPECT_TRUE(has("[Storey]   report: /runs/walk_storey/report.html", false));
  EXPECT_TRUE(has("[Storey] warning: IMU gap of 0.2 s", true));
  EXPECT_TRUE(has("[Storey] warning: scan dropped", true));
  for (const ConsoleLine& l : lines) {
    EXPECT_EQ(l.text.rfind("[Storey] ", 0), 0u) << l.text;
    EXPECT_EQ(l.text.find('|'), std::string::npos) << "no markdown table rows: " << l.text;
  }
}

}  // namespace
}  // namespace storey::plugin
