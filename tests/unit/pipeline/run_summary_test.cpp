// summariseRun on hand-written run reports: two storeys with their heights,
// warnings, the back end, map and storeys switched off; the aligned text.
#include "pipeline/run_summary.h"

#include <gtest/gtest.h>

#include <string>

#include "common/error.h"

namespace storey {
namespace {

std::string valueOf(const RunSummary& s, const std::string& label) {
  for (const RunSummary::Line& l : s.lines)
    if (l.label == label) return l.value;
  return "<no line '" + label + "'>";
}

const char* kTwoStoreys = R"({
  "input": {"log": "/data/walk.bag"},
  "odometry": {"scans": 1200},
  "log_duration_s": 120.04,
  "end_point_drift": {"dXYZ_m": 0.0421, "dXYZ_percent_of_path": 0.183, "path_length_m": 23.0},
  "backend": {"keyframes": 45, "planes": 12},
  "map": {"points": 123456, "voxel_size_m": 0.05},
  "storeys": [
    {"index": 0, "floor_elevation": -0.004, "clear_height": 2.71, "height": 3.02, "area": 88.4},
    {"index": 1, "floor_elevation": 3.016, "clear_height": null, "height": null, "area": 80.0}],
  "wall_time_s": 40.0, "wall_time_s_total": 47.5, "real_time_factor": 3.001,
  "warning_count": 3,
  "warnings": ["IMU gap of 0.2 s", "scan dropped", "1 more warnings not listed"],
  "files": ["map.las", "map.ply", "storeys/storey_00.las", "storeys/storey_01.las",
            "storeys.json", "trajectory.tum", "report.json"]})";

TEST(RunSummary, ReadsTheReport) {
  const RunSummary s = summariseRun(kTwoStoreys, "OUT");
  EXPECT_EQ(valueOf(s, "log"), "/data/walk.bag");
  EXPECT_EQ(valueOf(s, "duration"), "120.0 s of log, 1200 scans");
  EXPECT_EQ(valueOf(s, "path"), "23.0 m");
  EXPECT_EQ(valueOf(s, "end-point drift"), "0.042 m (0.18 % of the path)");
  EXPECT_EQ(valueOf(s, "back end"), "SRP: 45 keyframes, 12 planes");
  EXPECT_EQ(valueOf(s, "storeys"), "2 found");
  EXPECT_EQ(valueOf(s, "  storey 0"),
            "floor at 0.00 m, clear height 2.71 m, floor to floor 3.02 m, 88 m^2");
  EXPECT_EQ(valueOf(s, "  storey 1"), "floor at 3.02 m, no ceiling found, 80 m^2");
  EXPECT_EQ(valueOf(s, "map"), "123456 points, voxel 0.05 m");
  EXPECT_EQ(valueOf(s, "wall time"), "47.5 s in all; odometry and back end 40.0 s, 3.0x real time");
  EXPECT_EQ(valueOf(s, "warnings"), "3 (report.md)");
  EXPECT_EQ(s.warning_count, 3u);
  ASSERT_EQ(s.warnings.size(), 3u);
  EXPECT_EQ(s.warnings[0], "IMU gap of 0.2 s");
  EXPECT_EQ(valueOf(s, "report"), "OUT/report.html");
  EXPECT_EQ(valueOf(s, "map files"), "OUT/map.las, map.ply");
  EXPECT_EQ(valueOf(s, "storey files"), "OUT/storeys/ (2 files), OUT/storeys.json");
  EXPECT_EQ(valueOf(s, "trajectory"), "OUT/trajectory.tum");
}

TEST(RunSummary, SaysWhatIsSwitchedOff) {
  const RunSummary off = summariseRun(
      R"({"input": {"log": "a.bag"}, "backend": {"srp_requested": false}, "warning_count": 0,
          "warnings": []})",
      "OUT");
  EXPECT_EQ(valueOf(off, "back end"), "off: the trajectory is the odometry");
  EXPECT_EQ(valueOf(off, "map"), "off (map.enabled: false)");
  EXPECT_EQ(valueOf(off, "warnings"), "none");
  EXPECT_EQ(valueOf(off, "map files"), "<no line 'map files'>");
  const RunSummary no_storeys =
      summariseRun(R"({"map": {"points": 10, "voxel_size_m": 0.02}, "storeys": []})", "OUT");
  EXPECT_EQ(valueOf(no_storeys, "storeys"), "none found (report.md: map, segmentation)");
  EXPECT_THROW(summariseRun("[1, 2]", "OUT"), Error);
  EXPECT_THROW(summariseRun("not json", "OUT"), Error);
}

TEST(RunSummary, TextAlignsTheValues) {
  RunSummary s;
  s.lines = {{"log", "a.bag"}, {"end-point drift", "0.1 m"}, {"  storey 0", "floor at 0.00 m"}};
  EXPECT_EQ(s.text(),
            "  log              a.bag\n"
            "  end-point drift  0.1 m\n"
            "    storey 0       floor at 0.00 m\n");
  EXPECT_EQ(s.text(""),
            "log              a.bag\nend-point drift  0.1 m\n  storey 0       floor at 0.00 m\n");
}

}  // namespace
}  // namespace storey
