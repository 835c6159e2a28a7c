// `storey eval` run as a program on files written by the test: the numbers of
// its table and JSON, and a one-line error with exit status 1 on bad input.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "eval/eval_report.h"
#include "sim/mesh.h"
#include "support/run_storey.h"
#include "unit/eval/eval_fixtures.h"

namespace storey {
namespace {

using test::eval::readText;
using test::eval::writeText;

using test::RunResult;
using test::runStorey;
const auto quoted = test::shellQuoted;

/// The line of `text` that starts (after blanks) with `first_word`.
std::string lineStartingWith(const std::string& text, const std::string& first_word) {
  std::istringstream lines(text);
  std::string line, word;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    if (in >> word && word == first_word) return line;
  }
  return "";
}

class EvalCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::eval::makeTempDir("cli");
    // Truth: a 20 m walk at 10 Hz that ends where it started; estimate: the
    // truth shifted by (0.3, -0.4, 0) (ATE 0.5 m unaligned, 0 aligned).
    for (int i = 0; i <= 200; ++i) {
      const double s = 0.1 * i, a = 2.0 * M_PI * i / 200.0;
      const Eigen::Vector3d p(5.0 * std::sin(a), 5.0 * (1.0 - std::cos(a)) / 1.6,
                              0.5 * std::sin(a));
      const Pose T = test::eval::yawPose(a, p);
      gt_.push_back({1700000000.0 + s, T});
      est_.push_back({1700000000.0 + s, Pose(T.rotation(), p + Eigen::Vector3d(0.3, -0.4, 0.0))});
    }
    writeTum(path("gt.tum"), gt_);
    writeTum(path("trajectory.tum"), est_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::string dir_;
  Trajectory gt_, est_;
};

TEST_F(EvalCli, TrajectoryTableAndJson) {
  const RunResult r = runStorey(
      "eval --gt " + quoted(path("gt.tum")) + " --est " + quoted(path("trajectory.tum")), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Matched poses: 201 of 201"), std::string::npos) << r.out;
  std::istringstream none(lineStartingWith(r.out, "none"));
  std::string name;
  double rmse = -1, mean = -1, median = -1, max = -1;
  none >> name >> rmse >> mean >> median >> max;
  EXPECT_NEAR(rmse, 0.5, 1e-4) << r.out;
  EXPECT_NEAR(max, 0.5, 1e-4) << r.out;
  std::istringstream se3(lineStartingWith(r.out, "se3"));
  se3 >> name >> rmse;
  EXPECT_NEAR(rmse, 0.0, 1e-4) << r.out;

  // Default JSON: <est stem>.eval.json next to the estimate.
  const nlohmann::json json = nlohmann::json::parse(readText(path("trajectory.eval.json")));
  EXPECT_EQ(json["association"]["matched"], 201);
  EXPECT_EQ(json["ate"][0]["alignment"], "none");
  EXPECT_NEAR(json["ate"][0]["translation_m"]["rmse"].get<double>(), 0.5, 1e-8);
  EXPECT_NEAR(json["ate"][1]["translation_m"]["rmse"].get<double>(), 0.0, 1e-8);
  EXPECT_EQ(json["rpe"][0]["segment_length_m"], 10.0);
  EXPECT_GT(json["rpe"][0]["segments"].get<int>(), 0);
  EXPECT_NEAR(json["rpe"][0]["translation_percent"]["max"].get<double>(), 0.0, 1e-6);
  EXPECT_NEAR(json["drift"]["ground_truth"]["dxyz_m"].get<double>(), 0.0, 1e-6);
  EXPECT_TRUE(json["map"].is_null());
  EXPECT_TRUE(json["storeys"].is_null());
}

TEST_F(EvalCli, StoreysJsonNextToTheEstimateAndMapAgainstMesh) {
  writeText(path("truth.yaml"),
            "storeys:\n  - index: 0\n    floor_z: 0.0\n    ceiling_z: 2.8\n"
            "  - index: 1\n    floor_z: 3.0\n    ceiling_z: 5.8\n");
  writeText(
      path("storeys.json"),
      R"({"storeys": [{"index": 0, "floor_elevation": 0.01}, {"index": 1, "floor_elevation": 2.97}]})");
  sim::TriangleMesh mesh;
  mesh.addBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), sim::Surface::kWall);
  mesh.writePly(path("building.ply"));
  // Map: four points 0.01, 0.02, 0.03 and 0.10 m above the cube's top face.
  writeText(
      path("map.ply"),
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0.5 0.5 1.01\n0.2 0.2 1.02\n0.7 0.4 1.03\n0.5 0.5 1.1\n");
  const RunResult r =
      runStorey("eval --gt " + quoted(path("gt.tum")) + " --est " + quoted(path("trajectory.tum")) +
                    " --storeys " + quoted(path("truth.yaml")) + " --mesh " +
                    quoted(path("building.ply")) + " --map " + quoted(path("map.ply")),
                dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Storeys: 2 true, 2 estimated, 0 missed, 0 extra; max |error| 0.030 m"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("Map to mesh (m): 4 points, 12 triangles"), std::string::npos) << r.out;
  const nlohmann::json json = nlohmann::json::parse(readText(path("trajectory.eval.json")));
  const nlohmann::json& d = json["map"]["distance_m"];
  EXPECT_NEAR(d["mean"].get<double>(), 0.04, 1e-6);    // float coordinates
  EXPECT_NEAR(d["median"].get<double>(), 0.02, 1e-6);  // nearest rank of 4
  EXPECT_NEAR(d["max"].get<double>(), 0.10, 1e-6);
  EXPECT_NEAR(json["map"]["fraction_within"].get<double>(), 0.75, 1e-12);
  EXPECT_NEAR(json["storeys"]["storeys"][1]["error_m"].get<double>(), -0.03, 1e-12);
}

TEST_F(EvalCli, MalformedTumLineIsAOneLineErrorWithExitStatus1) {
  std::string text = readText(path("trajectory.tum"));
  text.insert(text.find('\n') + 1, "1700000000.05 1.0 2.0 x\n");  // line 2
  writeText(path("bad.tum"), text);
  const RunResult r = runStorey(
      "eval --gt " + quoted(path("gt.tum")) + " --est " + quoted(path("bad.tum")) + " --json none",
      dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(path("bad.tum") + " line 2"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("bad.eval.json")));
}

TEST_F(EvalCli, DifferentClocksAreAnErrorNamingBothFiles) {
  Trajectory relative = est_;
  for (StampedPose& s : relative) s.time -= 1700000000.0;
  writeTum(path("relative.tum"), relative);
  const RunResult r = runStorey(
      "eval --gt " + quoted(path("gt.tum")) + " --est " + quoted(path("relative.tum")), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(path("relative.tum") + " against " + path("gt.tum")), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("only 0 estimated poses"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace storey
