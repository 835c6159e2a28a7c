// `storey render` as a program with no DISPLAY (a private Xvfb is started):
// on a hand-made run with SRP hulls, and on the `tiny` preset's real run.
// Every PNG has the requested size and is not one flat colour; the SRP map
// holds exactly one palette colour per SRP of planes.json.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "png_check.h"
#include "render/palette.h"
#include "support/run_storey.h"
#include "support/temp_dir.h"
#include "unit/render/render_fixture.h"

namespace storey {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

int planeCount(const fs::path& planes_json) {
  const auto j = nlohmann::json::parse(readText(planes_json));
  return static_cast<int>(j.at("planes").size());
}

/// Checks every PNG of dir/renders; returns their names.
std::vector<std::string> checkPngs(const fs::path& dir, int width, int height) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir / "renders")) {
    if (entry.path().extension() != ".png") continue;
    names.push_back(entry.path().filename().string());
    const test::Image image = test::readPng(entry.path().string());
    EXPECT_EQ(image.width, width) << entry.path();
    EXPECT_EQ(image.height, height) << entry.path();
    if (image.width == 0) continue;
    const auto scene = test::coloursIn(image, render::figureLayout(width, height).scene);
    EXPECT_GT(scene.size(), 8u) << entry.path() << ": (nearly) one flat colour";
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// SRP palette colours (ids 0..n+9) present in the scene area of srp_map.png.
void expectSrpColours(const fs::path& png, int planes, int width, int height) {
  const test::Image image = test::readPng(png.string());
  ASSERT_EQ(image.width, width) << png;
  const auto scene = test::coloursIn(image, render::figureLayout(width, height).scene);
  int present = 0, extra = 0;
  for (int id = 0; id < planes + 10; ++id) {
    const bool in = scene.count(test::key(render::srpColour(id))) > 0;
    if (id < planes) {
      present += in;
      EXPECT_TRUE(in) << "SRP " << id << " is not visible in " << png;
    } else {
      extra += in;
    }
  }
  EXPECT_EQ(present, planes);
  EXPECT_EQ(extra, 0) << "palette colours of SRP ids that do not exist";
}

class RenderCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ::unsetenv("DISPLAY");  // no X server: storey must start its own Xvfb
    dir_ = new test::TempDir();
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static test::TempDir* dir_;
};
test::TempDir* RenderCli::dir_ = nullptr;

TEST_F(RenderCli, HandMadeRunWithHullsWithoutDisplay) {
  const std::string run = dir_->file("room");
  const int planes = test::writeRoomRun(run);
  const auto r =
      test::runStorey("render " + run + " --width 800 --height 500", dir_->path().string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto names = checkPngs(run, 800, 500);
  EXPECT_EQ(names, (std::vector<std::string>{"elevation_front.png", "elevation_side.png",
                                             "srp_keyframe_0000.png", "srp_map.png",
                                             "storey_00_top.png"}));
  expectSrpColours(fs::path(run) / "renders" / "srp_map.png", planes, 800, 500);
  const std::string md = readText(fs::path(run) / "report.md");
  for (const auto& name : names)
    EXPECT_NE(md.find("](renders/" + name + ")"), std::string::npos) << name;
  const std::string html = readText(fs::path(run) / "report.html");
  EXPECT_NE(html.find("<img src=\"renders/srp_map.png\""), std::string::npos);

  // One keyframe, one view; the other keyframe's SRPs are not in colour.
  const auto k =
      test::runStorey("render " + run + " --views keyframe --keyframe 1 --width 640 --height 400",
                      dir_->path().string());
  ASSERT_EQ(k.exit_code, 0) << k.out << k.err;
  EXPECT_EQ(checkPngs(run, 640, 400), (std::vector<std::string>{"srp_keyframe_0001.png"}));
  const test::Image image =
      test::readPng((fs::path(run) / "renders" / "srp_keyframe_0001.png").string());
  const auto scene = test::coloursIn(image, render::figureLayout(640, 400).scene);
  for (int id : {0, 2, 3, 5}) EXPECT_TRUE(scene.count(test::key(render::srpColour(id)))) << id;
  for (int id : {1, 4}) EXPECT_FALSE(scene.count(test::key(render::srpColour(id)))) << id;
}

TEST_F(RenderCli, BadRequestsFailWithAMessage) {
  const std::string run = dir_->file("room2");
  test::writeRoomRun(run);
  auto r = test::runStorey("render " + run + " --keyframe 7", dir_->path().string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("keyframes.tum has 2 keyframes"), std::string::npos) << r.err;
  r = test::runStorey("render " + run + " --views srp,nonsense", dir_->path().string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("nonsense"), std::string::npos) << r.err;
  r = test::runStorey("render " + dir_->file("missing"), dir_->path().string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("missing"), std::string::npos) << r.err;
  r = test::runStorey("render " + run + " --width 100", dir_->path().string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("render.width"), std::string::npos) << r.err;
}

TEST_F(RenderCli, TinyPresetRunWithGroundTruth) {
  const std::string sim = dir_->file("sim"), out = dir_->file("out");
  auto r = test::runStorey("simulate tiny -o " + sim + " --no-progress --threads 2",
                           dir_->path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::runStorey("run " + sim + "/simulation.bag --calibration " + sim +
                          "/calibration.yaml -o " + out + " --no-render",
                      dir_->path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_FALSE(fs::exists(fs::path(out) / "renders")) << "--no-render still rendered";
  ASSERT_TRUE(fs::exists(fs::path(out) / "planes.json"));
  r = test::runStorey(
      "render " + out + " --width 960 --height 600 --gt " + sim + "/groundtruth_lidar.tum",
      dir_->path().string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto names = checkPngs(out, 960, 600);
  for (const char* expected : {"elevation_front.png", "elevation_side.png", "srp_map.png",
                               "trajectories_top.png", "trajectories_front.png"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  expectSrpColours(fs::path(out) / "renders" / "srp_map.png",
                   planeCount(fs::path(out) / "planes.json"), 960, 600);
  EXPECT_TRUE(fs::exists(fs::path(out) / "report.html"));
  EXPECT_NE(readText(fs::path(out) / "report.md").find("](renders/srp_map.png)"),
            std::string::npos);
}

}  // namespace
}  // namespace storey
