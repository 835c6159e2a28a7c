// Floor elevation error per storey: the simulator's storeys.yaml against a
// storeys.json, and the orchestrator's skip messages.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/error.h"
#include "eval/evaluation.h"
#include "eval/storey_error.h"
#include "unit/eval/eval_fixtures.h"

namespace storey::eval {
namespace {

using test::eval::writeText;

class EvalStoreys : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::eval::makeTempDir("storeys"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::string dir_;
};

// As core/sim/simulator.cpp writes it.
const char* kTruthYaml =
    "# Storey simulator ground truth: the storeys of the building.\n"
    "building: test\nseed: 7\nstoreys:\n"
    "  - index: 0\n    floor_z: 0.000000\n    ceiling_z: 2.800000\n"
    "  - index: 1\n    floor_z: 3.000000\n    ceiling_z: 5.800000\n"
    "  - index: 2\n    floor_z: 6.000000\n    ceiling_z: 8.800000\n";

TEST_F(EvalStoreys, ErrorPerStoreyMatchedByElevation) {
  writeText(path("truth.yaml"), kTruthYaml);
  writeText(path("storeys.json"),
            R"({"storeys": [{"index": 1, "floor_elevation": 3.04, "height": 2.7},
                            {"index": 0, "floor_elevation": -0.02, "area": 120.5}]})");
  const StoreyComparison c = compareStoreys(readTrueStoreys(path("truth.yaml")),
                                            readEstimatedStoreys(path("storeys.json")));
  EXPECT_EQ(c.true_storeys, 3u);
  EXPECT_EQ(c.estimated_storeys, 2u);
  EXPECT_EQ(c.missed, 1u);
  EXPECT_EQ(c.extra, 0u);
  ASSERT_EQ(c.storeys.size(), 3u);
  EXPECT_EQ(*c.storeys[0].estimated_index, 0);
  EXPECT_NEAR(c.storeys[0].error, -0.02, 1e-12);
  EXPECT_NEAR(c.storeys[1].error, 0.04, 1e-12);
  EXPECT_FALSE(c.storeys[2].estimated_index.has_value());
  EXPECT_NEAR(c.max_abs_error, 0.04, 1e-12);
}

TEST_F(EvalStoreys, IndicesNeedNotAgreeAndFarFloorsAreExtra) {
  const std::vector<StoreyLevel> truth = {{0, 0.0}, {1, 3.0}};
  const std::vector<StoreyLevel> estimate = {{5, 3.01}, {6, 0.03}, {7, 10.0}};
  const StoreyComparison c = compareStoreys(truth, estimate, 0.5);
  EXPECT_EQ(*c.storeys[0].estimated_index, 6);
  EXPECT_EQ(*c.storeys[1].estimated_index, 5);
  EXPECT_EQ(c.extra, 1u);
  EXPECT_EQ(c.missed, 0u);
}

TEST_F(EvalStoreys, BadFilesAreErrorsNamingFileAndEntry) {
  writeText(path("bad.json"),
            R"({"storeys": [{"index": 0, "floor_elevation": 0.1}, {"index": 1}]})");
  try {
    readEstimatedStoreys(path("bad.json"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path("bad.json") + ": storeys[1]"), std::string::npos)
        << e.what();
  }
  writeText(path("broken.json"), "{\"storeys\": [");
  EXPECT_THROW(readEstimatedStoreys(path("broken.json")), Error);
  writeText(path("bad.yaml"), "storeys:\n  - index: 0\n    floor_z: high\n");
  try {
    readTrueStoreys(path("bad.yaml"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("storeys[0] (line 2)"), std::string::npos) << e.what();
  }
  // A top-level array is accepted too.
  writeText(path("array.json"), R"([{"index": 0, "floor_elevation": 0.5}])");
  EXPECT_EQ(readEstimatedStoreys(path("array.json")).size(), 1u);
}

TEST_F(EvalStoreys, TruthAloneIsSkippedWithANote) {
  Trajectory walk;
  for (int i = 0; i < 10; ++i)
    walk.push_back({1.0 * i, Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(i, 0, 0))});
  writeTum(path("gt.tum"), walk);
  writeText(path("truth.yaml"), kTruthYaml);
  EvaluationInputs inputs;
  inputs.gt_path = inputs.est_path = path("gt.tum");
  inputs.true_storeys_path = path("truth.yaml");
  const EvaluationResult result = evaluate(inputs);
  EXPECT_FALSE(result.storeys.has_value());
  ASSERT_FALSE(result.notes.empty());
  EXPECT_EQ(result.notes.front(), "storeys: skipped (no estimated storeys.json given or found)");
  EXPECT_FALSE(result.map.has_value());
}

}  // namespace
}  // namespace storey::eval
