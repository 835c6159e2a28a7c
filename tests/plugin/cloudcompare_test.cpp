// The plugin inside Debian's real CloudCompare 2.11.3, on the tiny simulated
// log (ctest fixture plugin_simulate_tiny):
// - command line, headless (QT_QPA_PLATFORM=offscreen): -STOREY_SLAM then
//   CloudCompare's own -SAVE_CLOUDS; the saved clouds are checked against the
//   core's own map.ply of the same run (point count) and field by field;
// - bad arguments and a bad log fail with exit code 1 and a message;
// - the GUI under Xvfb, run through the plugin's test hook
//   (STOREY_PLUGIN_AUTORUN), with a screenshot of the whole screen.
// Every CloudCompare run gets a temporary HOME and XDG_DATA_HOME; the plugin
// is copied into $XDG_DATA_HOME/CCCorp/CloudCompare/plugins (no root).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/temp_dir.h"

namespace {

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr
};

std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

Result shell(const std::string& command) {
  Result r;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    r.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// A private HOME with the plugin installed in the user's plugin folder.
class CloudCompareHome {
 public:
  CloudCompareHome() {
    const fs::path plugins = dir_.path() / "xdg/CCCorp/CloudCompare/plugins";
    fs::create_directories(plugins);
    fs::copy_file(STOREY_PLUGIN_FILE, plugins / fs::path(STOREY_PLUGIN_FILE).filename());
  }
  /// `env` with the private HOME, XDG_DATA_HOME and XDG_CONFIG_HOME.
  std::string env(const std::string& env_options = "") const {
    return "env " + env_options +
           " " STOREY_CLOUDCOMPARE_ENV " HOME=" + quoted(dir_.path().string()) +
           " XDG_DATA_HOME=" + quoted((dir_.path() / "xdg").string()) +
           " XDG_CONFIG_HOME=" + quoted((dir_.path() / "config").string());
  }
  /// Headless command-line run.
  Result run(const std::string& args) const {
    return shell("cd " + quoted(dir_.path().string()) + " && " + env() +
                 " QT_QPA_PLATFORM=offscreen " + quoted(STOREY_CLOUDCOMPARE) + " -SILENT " + args);
  }
  std::string file(const std::string& name) const { return dir_.file(name); }

 private:
  storey::test::TempDir dir_;
};

const std::string kLog = std::string(STOREY_TINY_DIR) + "/simulation.bag";

/// The tiny building's one floor is smaller than the default storeys.min_floor_area
/// (10 m^2) once the walls and clutter are taken out: a config lowers it, which
/// also exercises -STOREY_CONFIG.
std::string smallFloorConfig(const CloudCompareHome& home) {
  const std::string path = home.file("small_floor.yaml");
  std::ofstream(path) << "storeys:\n  min_floor_area: 3.0\n";
  return path;
}

/// An ASCII PLY: its vertex properties and rows.
struct Ply {
  std::vector<std::string> properties;
  std::vector<std::vector<double>> rows;
  std::size_t declared = 0;
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < properties.size(); ++i)
      if (properties[i] == name) return static_cast<int>(i);
    return -1;
  }
};

Ply readPly(const std::string& path, bool read_rows) {
  Ply ply;
  std::ifstream in(path);
  std::string line;
  bool in_vertex = false;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "element") {
      std::string what;
      ls >> what;
      in_vertex = what == "vertex";
      if (in_vertex) ls >> ply.declared;
    } else if (word == "property" && in_vertex) {
      std::string type, name;
      ls >> type >> name;
      ply.properties.push_back(name);
    }
  }
  if (!read_rows) return ply;
  for (std::size_t i = 0; i < ply.declared && std::getline(in, line); ++i) {
    std::istringstream ls(line);
    std::vector<double> row;
    double v;
    while (ls >> v) row.push_back(v);
    ply.rows.push_back(std::move(row));
  }
  return ply;
}

/// `CloudCompare -STOREY_SLAM LOG` into `out` with the small-floor config,
/// every cloud saved as ASCII PLY.
Result mapWithCloudCompare(const CloudCompareHome& home, const std::string& log,
                           const std::string& out) {
  return home.run("-AUTO_SAVE OFF -NO_TIMESTAMP -STOREY_SLAM " + quoted(log) + " -STOREY_CONFIG " +
                  quoted(smallFloorConfig(home)) + " -STOREY_OUT " + quoted(out) +
                  " -C_EXPORT_FMT PLY -PLY_EXPORT_FMT ASCII -SAVE_CLOUDS");
}

TEST(PluginCommandLine, MapsTheTinyLogAndHandsTheCloudsToCloudCompare) {
  ASSERT_TRUE(fs::exists(kLog)) << kLog << " (fixture plugin_simulate_tiny)";
  CloudCompareHome home;
  const std::string out = home.file("out");
  const Result r = mapWithCloudCompare(home, kLog, out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("[Storey] done in"), std::string::npos) << r.output;

  // The core's own outputs of the same run are there too.
  ASSERT_TRUE(fs::exists(out + "/map.ply")) << r.output;
  const Ply core_map = readPly(out + "/map.ply", false);
  ASSERT_GT(core_map.declared, 10000u)
      << "a tiny corridor loop maps to tens of thousands of voxels";

  // The map as CloudCompare saved it: same points as the core's map.ply,
  // with the plugin's scalar fields.
  const std::string map_path = out + "/simulation_map.ply";
  ASSERT_TRUE(fs::exists(map_path)) << r.output;
  const Ply map = readPly(map_path, true);
  EXPECT_EQ(map.declared, core_map.declared);
  ASSERT_EQ(map.rows.size(), map.declared);
  for (const char* field : {"intensity", "storey", "time", "keyframe", "flags"})
    EXPECT_GE(map.column(std::string("scalar_") + field), 0)
        << field << " missing from " << map_path;
  const int time = map.column("scalar_time");
  const int storey = map.column("scalar_storey");
  ASSERT_GE(time, 0);
  ASSERT_GE(storey, 0);
  double t_max = 0.0;
  for (const auto& row : map.rows) {
    ASSERT_EQ(row.size(), map.properties.size());
    ASSERT_GE(row[static_cast<std::size_t>(time)], -1e-3) << "time is relative to the first scan";
    t_max = std::max(t_max, row[static_cast<std::size_t>(time)]);
  }
  EXPECT_GT(t_max, 5.0) << "the tiny walk lasts about 20 s";
  EXPECT_LT(t_max, 120.0);

  // One cloud per storey, each holding only its storey's points; together
  // they hold every labelled point of the map.
  std::size_t labelled = 0;
  for (const auto& row : map.rows) labelled += row[static_cast<std::size_t>(storey)] >= 0 ? 1 : 0;
  std::size_t in_storeys = 0;
  int storeys = 0;
  for (int s = 0; fs::exists(out + "/simulation_storey_0" + std::to_string(s) + ".ply"); ++s) {
    const Ply cloud = readPly(out + "/simulation_storey_0" + std::to_string(s) + ".ply", true);
    const int column = cloud.column("scalar_storey");
    ASSERT_GE(column, 0);
    for (const auto& row : cloud.rows) ASSERT_EQ(row[static_cast<std::size_t>(column)], s);
    in_storeys += cloud.rows.size();
    ++storeys;
  }
  EXPECT_GE(storeys, 1) << "the tiny building has one storey";
  EXPECT_EQ(in_storeys, labelled);
}

// A rosbag2 folder (MCAP storage), its calibration beside it as `storey
// simulate --ros2` writes it: read by content, mapped, handed to CloudCompare.
TEST(PluginCommandLine, MapsARos2BagFolder) {
  const std::string log = std::string(STOREY_TINY_ROS2_DIR) + "/simulation_ros2";
  ASSERT_TRUE(fs::is_directory(log)) << log << " (fixture plugin_simulate_tiny_ros2)";
  CloudCompareHome home;
  const std::string out = home.file("out");
  const Result r = mapWithCloudCompare(home, log, out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("[Storey] done in"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(out + "/map.ply")) << r.output;
  EXPECT_GT(readPly(out + "/map.ply", false).declared, 5000u);
  // 8 s of a 10 Hz LiDAR, every scan registered.
  std::ifstream trajectory(out + "/trajectory.tum");
  int poses = 0;
  for (std::string line; std::getline(trajectory, line);) poses += !line.empty() && line[0] != '#';
  EXPECT_GE(poses, 70) << r.output;
}

TEST(PluginCommandLine, MissingLogFailsCleanly) {
  CloudCompareHome home;
  const Result r = home.run("-AUTO_SAVE OFF -STOREY_SLAM /nonexistent/walk.bag");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/walk.bag: no such file"), std::string::npos) << r.output;
}

TEST(PluginCommandLine, BadArgumentsFailWithUsage) {
  CloudCompareHome home;
  Result r = home.run("-AUTO_SAVE OFF -STOREY_SLAM");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("missing LOG"), std::string::npos) << r.output;
  r = home.run("-AUTO_SAVE OFF -STOREY_SLAM " + quoted(kLog) + " -STOREY_CONFIG");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("missing value after -STOREY_CONFIG"), std::string::npos) << r.output;
}

TEST(PluginCommandLine, BadConfigKeyIsNamed) {
  CloudCompareHome home;
  const std::string config = home.file("bad.yaml");
  std::ofstream(config) << "map:\n  voxel_sise: 0.05\n";
  const Result r = home.run("-AUTO_SAVE OFF -STOREY_SLAM " + quoted(kLog) + " -STOREY_CONFIG " +
                            quoted(config) + " -STOREY_OUT " + quoted(home.file("out")));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("voxel_sise"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(home.file("out/report.json"))) << "nothing is written on a bad config";
}

/// CloudCompare's GUI under a private Xvfb with the plugin's test hook
/// (docs/plugin.md) running the run action on the tiny log; `hook` adds
/// STOREY_PLUGIN_* variables. Xvfb picks a free display itself (-displayfd)
/// and is stopped by its PID at the end, so parallel tests neither collide
/// nor leave servers behind.
Result runGui(const CloudCompareHome& home, const std::string& hook) {
  const std::string dir = quoted(home.file(""));
  return shell(
      "cd " + dir +
      " && { Xvfb -displayfd 3 -screen 0 1600x1000x24 -nolisten tcp 3>display "
      ">xvfb.log 2>&1 & x=$!; i=0; while [ ! -s display ] && [ $i -lt 200 ]; do sleep 0.1; "
      "i=$((i+1)); done; DISPLAY=:$(cat display) " +
      home.env("-u QT_QPA_PLATFORM") + " STOREY_PLUGIN_AUTORUN=" + quoted(kLog) +
      " STOREY_PLUGIN_AUTORUN_OUT=" + quoted(home.file("out")) +
      " STOREY_PLUGIN_AUTORUN_CONFIG=" + quoted(smallFloorConfig(home)) +
      " STOREY_PLUGIN_AUTORUN_DONE=" + quoted(home.file("done.txt")) +
      " STOREY_PLUGIN_AUTORUN_QUIT=1 STOREY_PLUGIN_AUTORUN_TIMEOUT=240 " + hook + " timeout 300 " +
      quoted(STOREY_CLOUDCOMPARE) + "; rc=$?; kill $x; wait $x; exit $rc; }");
}

TEST(PluginGui, RunActionUnderXvfbPutsTheRunInTheDbTree) {
  if (shell("command -v Xvfb").exit_code != 0) GTEST_SKIP() << "Xvfb is not installed";
  CloudCompareHome home;
  const std::string done = home.file("done.txt");
  fs::remove(STOREY_SCREENSHOT);
  const Result r = runGui(home,
                          "STOREY_PLUGIN_AUTORUN_INSPECT=1 STOREY_PLUGIN_AUTORUN_KEYFRAME=0 "
                          "STOREY_PLUGIN_AUTORUN_EXPORT=" +
                              quoted(home.file("export")) +
                              " STOREY_PLUGIN_SCREENSHOT=" + quoted(STOREY_SCREENSHOT));
  ASSERT_TRUE(fs::exists(done)) << "exit " << r.exit_code << "\n" << r.output;
  std::ifstream in(done);
  std::map<std::string, std::vector<std::string>> lines;
  std::string kind, rest;
  while (in >> kind && std::getline(in, rest)) lines[kind].push_back(rest);
  ASSERT_EQ(lines.count("map"), 1u) << "the run failed: see " << done;
  std::istringstream map_line(lines["map"][0]);
  std::string name;
  std::size_t points = 0;
  map_line >> name >> name >> points;  // "<stem> map <points>"
  EXPECT_GT(points, 10000u);
  EXPECT_GE(lines["storey"].size(), 1u);
  std::size_t planes = std::stoul(lines["planes"].at(0));
  EXPECT_GE(planes, 1u) << "the SRP back end finds the corridor's walls and floor";
  // "Inspect SRPs" labelled the points on the planes; "Export storeys" wrote
  // LAS + PLY per storey from the cloud in the DB tree.
  ASSERT_EQ(lines.count("srp_points"), 1u);
  EXPECT_GT(std::stoul(lines["srp_points"][0]), 1000u);
  EXPECT_LT(std::stoul(lines["srp_points"][0]), points);
  EXPECT_EQ(lines.count("error:"), 0u);
  // "planes seen from a keyframe": keyframe 0 (the still start) sees at least
  // the floor; exactly the planes it observed stay visible.
  ASSERT_EQ(lines.count("keyframe_planes"), 1u);
  std::istringstream keyframe_line(lines["keyframe_planes"][0]);
  std::size_t observed = 0, visible = 0;
  keyframe_line >> observed >> visible;
  EXPECT_GE(observed, 1u);
  EXPECT_EQ(visible, observed);
  EXPECT_LT(visible, planes) << "a keyframe does not see every SRP of the run";
  EXPECT_TRUE(fs::exists(home.file("export/storey_00.las")));
  EXPECT_TRUE(fs::exists(home.file("export/storey_00.ply")));
  // The console: the run summary as readable lines (no markdown table rows),
  // with the storeys and the path of report.html.
  const std::vector<std::string>& console = lines["console"];
  ASSERT_GE(console.size(), 8u) << "see " << done;
  EXPECT_NE(console[0].find("[Storey] done in"), std::string::npos) << console[0];
  auto shown = [&console](const std::string& text) {
    for (const std::string& line : console)
      if (line.find(text) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(shown("[Storey]   storeys: ")) << "see " << done;
  EXPECT_TRUE(shown("[Storey]     storey 0: floor at ")) << "see " << done;
  EXPECT_TRUE(shown("[Storey]   map: " + std::to_string(points) + " points"));
  EXPECT_TRUE(shown("[Storey]   report: " + home.file("out/report.html"))) << "see " << done;
  EXPECT_TRUE(fs::exists(home.file("out/report.html")));
  for (const std::string& line : console)
    EXPECT_EQ(line.find('|'), std::string::npos) << "markdown in the console: " << line;
  for (const std::string& line : lines["console_warning"])
    EXPECT_EQ(line.find(" [Storey] warning: "), 0u) << line;
  // The progress dialog showed the stage, the elapsed time and the time left.
  ASSERT_EQ(lines.count("progress"), 1u) << "see " << done;
  const std::string& progress = lines["progress"][0];
  EXPECT_NE(progress.find("Storey SLAM: "), std::string::npos) << progress;
  EXPECT_NE(progress.find(" elapsed, "), std::string::npos) << progress;
  EXPECT_NE(progress.find(" left"), std::string::npos) << progress;
  ASSERT_TRUE(fs::exists(STOREY_SCREENSHOT));
  EXPECT_GT(fs::file_size(STOREY_SCREENSHOT), 20000u) << "a screenshot of the whole window";
}

TEST(PluginGui, CancelInTheProgressDialogStopsTheRunAndWritesNothing) {
  if (shell("command -v Xvfb").exit_code != 0) GTEST_SKIP() << "Xvfb is not installed";
  CloudCompareHome home;
  const Result r = runGui(home, "STOREY_PLUGIN_AUTORUN_CANCEL=1");
  std::ifstream in(home.file("done.txt"));
  std::string summary;
  std::getline(in, summary);
  EXPECT_EQ(summary, "cancelled") << r.output;
  EXPECT_FALSE(fs::exists(home.file("out/report.json")));
  EXPECT_FALSE(fs::exists(home.file("out/map.ply")));
}

TEST(PluginGui, BadConfigFileStopsTheRunWithItsKey) {
  if (shell("command -v Xvfb").exit_code != 0) GTEST_SKIP() << "Xvfb is not installed";
  CloudCompareHome home;
  const std::string config = home.file("bad.yaml");
  std::ofstream(config) << "backend:\n  srp: maybe\n";
  // Given after runGui's own config variable, this one wins.
  const Result r = runGui(home, "STOREY_PLUGIN_AUTORUN_CONFIG=" + quoted(config));
  std::ifstream in(home.file("done.txt"));
  std::string summary;
  std::getline(in, summary);
  EXPECT_EQ(summary.rfind("error: ", 0), 0u) << summary << "\n" << r.output;
  EXPECT_NE(summary.find("srp"), std::string::npos) << summary;
  EXPECT_FALSE(fs::exists(home.file("out/report.json")));
}

}  // namespace
