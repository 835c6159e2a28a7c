// End to end on the `tiny` preset through runPipeline (what `storey run`
// does): simulate, odometry + back end, map from the keyframe scans at their
// optimised poses, storeys, exports; then core/eval: map-to-mesh distance and
// floor elevation against the simulator's truth. Also the switches: back end
// off (keyframes from the odometry), storeys off, map off.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "config/config.h"
#include "eval/evaluation.h"
#include "eval/storey_error.h"
#include "pipeline/pipeline.h"
#include "sim/simulator.h"
#include "support/tiny_simulation.h"

namespace storey {
namespace {

namespace fs = std::filesystem;

class MapEndToEnd : public test::TinySimulation {
 protected:
  static Config config() { return simConfig(); }
};

TEST_F(MapEndToEnd, TinyPresetMapMatchesTheMeshAndTheFloor) {
  const std::string out = file("out");
  const PipelineResult r = runPipeline(bag(), config(), out);
  ASSERT_TRUE(r.map);
  ASSERT_GE(r.keyframes.size(), 5u);
  EXPECT_GT(r.map->size(), 10000u);
  for (const char* f : {"map.las", "map.ply", "map.pcd", "storeys.json", "storeys/storey_00.las",
                        "storeys/storey_00.ply", "trajectory.tum", "odometry.tum", "keyframes.tum",
                        "trajectory_kitti.txt", "trajectory_kitti_times.txt", "planes.json",
                        "timing.csv", "report.json", "report.md"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
    EXPECT_NE(std::find(r.files.begin(), r.files.end(), f), r.files.end()) << f << " listed";
  }
  // Every map point comes from a keyframe of keyframes.tum and has its storey.
  for (std::size_t i = 0; i < r.map->size(); ++i) {
    ASSERT_GE(r.map->keyframe[i], 0);
    ASSERT_LT(r.map->keyframe[i], static_cast<int>(r.keyframes.size()));
  }
  EXPECT_EQ(readTum(out + "/keyframes.tum").size(), r.keyframes.size());
  // timing.csv: a line per scan of the trajectory; the keyframes flagged
  // (all but the last scan, which finish() makes the last keyframe).
  std::ifstream timing(out + "/timing.csv");
  std::string line;
  std::getline(timing, line);
  EXPECT_EQ(line, "time,odometry_ms,backend_ms,keyframe");
  std::size_t timed_scans = 0, timed_keyframes = 0;
  while (std::getline(timing, line)) {
    ++timed_scans;
    timed_keyframes += line.back() == '1';
  }
  EXPECT_EQ(timed_scans, r.trajectory.size());
  EXPECT_GE(timed_keyframes + 1, r.keyframes.size());
  EXPECT_LE(timed_keyframes, r.keyframes.size());
  // The last scan is a keyframe (the end of the walk is in the map).
  EXPECT_DOUBLE_EQ(r.keyframes.back().time, r.trajectory.back().time);

  const eval::MapEvaluation map = eval::evaluateMap(simFile(sim::kMeshFile), out + "/map.ply");
  EXPECT_EQ(map.points, r.map->size());
  EXPECT_LT(map.distance.median, 0.03);
  RecordProperty("median_map_to_mesh_m", std::to_string(map.distance.median));

  const auto truth = eval::readTrueStoreys(simFile(sim::kStoreysFile));
  const auto estimate = eval::readEstimatedStoreys(out + "/storeys.json");
  ASSERT_EQ(truth.size(), 1u);
  ASSERT_EQ(estimate.size(), 1u);
  ASSERT_EQ(r.storeys.size(), 1u);
  const eval::StoreyComparison storeys = eval::compareStoreys(truth, estimate);
  EXPECT_EQ(storeys.missed, 0u);
  EXPECT_LT(storeys.max_abs_error, 0.05);

  // The report has the map and storey sections and lists the files.
  const auto report = nlohmann::json::parse(test::readText(out + "/report.json"));
  EXPECT_EQ(report.at("map").at("points").get<std::size_t>(), r.map->size());
  EXPECT_EQ(report.at("storeys").size(), 1u);
  EXPECT_TRUE(report.contains("files"));
  const std::string md = test::readText(out + "/report.md");
  EXPECT_NE(md.find("Table I"), std::string::npos);
  EXPECT_NE(md.find("Table II"), std::string::npos);

  // planes.json observations carry the patch each keyframe saw.
  const auto planes = nlohmann::json::parse(test::readText(out + "/planes.json"));
  ASSERT_FALSE(planes.at("planes").empty());
  for (const auto& p : planes.at("planes"))
    for (const auto& o : p.at("observations")) {
      EXPECT_GE(o.at("hull").size(), 3u);
      EXPECT_EQ(o.at("centroid").size(), 3u);
    }
}

TEST_F(MapEndToEnd, SwitchesBackEndOffStoreysOffAndMapOff) {
  // Back end off: keyframes by the same rule on the odometry; no planes.json.
  Config c = config();
  c.backend.srp = false;
  c.storeys.enabled = false;
  const std::string out = file("out_nosrp");
  fs::create_directories(out);
  writeFileAtomically(out + "/planes.json", "{}\n");  // a previous run's
  const PipelineResult r = runPipeline(bag(), c, out);
  ASSERT_TRUE(r.map);
  EXPECT_GE(r.keyframes.size(), 5u);
  EXPECT_FALSE(r.planes);
  EXPECT_FALSE(fs::exists(out + "/planes.json")) << "a stale planes.json would be misleading";
  EXPECT_TRUE(fs::exists(out + "/map.las"));
  EXPECT_TRUE(r.storeys.empty());
  for (std::size_t i = 0; i < r.map->size(); ++i) ASSERT_EQ(r.map->storey[i], kNoStorey);
  EXPECT_FALSE(fs::exists(out + "/storeys/storey_00.las"));

  // Map off: trajectories and report only.
  c.map.enabled = false;
  const std::string out2 = file("out_nomap");
  const PipelineResult r2 = runPipeline(bag(), c, out2);
  EXPECT_FALSE(r2.map);
  EXPECT_TRUE(fs::exists(out2 + "/trajectory.tum"));
  EXPECT_TRUE(fs::exists(out2 + "/report.md"));
  EXPECT_FALSE(fs::exists(out2 + "/map.las"));
}

}  // namespace
}  // namespace storey
