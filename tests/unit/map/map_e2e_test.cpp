// End to end on the `tiny` preset: simulate, odometry (the pipeline's front-end
// loop, tests/unit/map/map_dev.cpp, until runPipeline runs the map stage
// itself), map from the keyframe scans at their poses, exports, then
// core/eval: map-to-mesh distance and floor elevation against the truth.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/log.h"
#include "config/calibration.h"
#include "eval/evaluation.h"
#include "eval/storey_error.h"
#include "export/map_export.h"
#include "map_dev.h"
#include "sim/simulator.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

TEST(MapEndToEnd, TinyPresetMapMatchesTheMeshAndTheFloor) {
  test::TempDir dir;
  const std::string sim_dir = dir.file("sim");
  const std::string out = dir.file("out");
  sim::simulate(sim::loadBuildingSpec("tiny"), {}, sim_dir);
  Config config;
  applyCalibrationFile(config, sim_dir + "/" + sim::kCalibrationFile);
  const std::string bag = sim_dir + "/" + sim::kBagFile;

  MapBuilder builder(config.map);
  const test::DevRun run = test::runOdometryIntoMap(bag, config, builder);
  ASSERT_GE(run.keyframe_poses.size(), 5u);


  const MapOutputs outputs = buildAndExportMap(builder, run.keyframe_poses, config.storeys, out);
  EXPECT_GT(outputs.map_points, 10000u);
  for (const char* f : {"map.las", "map.ply", "map.pcd", "storeys.json", "storeys/storey_00.las",
                        "storeys/storey_00.ply"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;

  const eval::MapEvaluation map =
      eval::evaluateMap(sim_dir + "/" + sim::kMeshFile, out + "/map.ply");
  EXPECT_EQ(map.points, outputs.map_points);
  EXPECT_LT(map.distance.median, 0.03);
  RecordProperty("median_map_to_mesh_m", std::to_string(map.distance.median));

  const auto truth = eval::readTrueStoreys(sim_dir + "/" + sim::kStoreysFile);
  const auto estimate = eval::readEstimatedStoreys(out + "/storeys.json");
  ASSERT_EQ(truth.size(), 1u);
  ASSERT_EQ(estimate.size(), 1u);
  const eval::StoreyComparison storeys = eval::compareStoreys(truth, estimate);
  EXPECT_EQ(storeys.missed, 0u);
  EXPECT_LT(storeys.max_abs_error, 0.05);
}

}  // namespace
}  // namespace storey
