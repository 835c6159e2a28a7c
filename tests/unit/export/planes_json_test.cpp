// planes.json: the one writer and reader (export/planes_json.h). A plane map
// written and read back is the same map; the reader takes files without the
// optional fields and names the place of what is wrong.
#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "export/planes_json.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

PlaneMap sampleMap() {
  PlaneMap map;
  map.keyframes = 3;
  GlobalPlane wall;
  wall.id = 0;
  wall.normal_world = Eigen::Vector3d(1, 0, 0);
  wall.distance_world = 2.0;
  wall.facing_world = Eigen::Vector3d(-1, 0, 0);
  PlaneObservation seen;
  seen.keyframe = 2;
  seen.time = 12.25;
  seen.normal_keyframe = Eigen::Vector3d(0, -1, 0);
  seen.distance_keyframe = 1.9375;
  seen.centroid_keyframe = Eigen::Vector3d(0.5, -1.9375, 0.25);
  seen.hull_keyframe = {{-1, -1.9375, 0}, {3, -1.9375, 0}, {3, -1.9375, 1}};
  seen.points = 512;
  seen.fit_rms = 0.0125;
  seen.residual_chi2 = 7.5;
  seen.outlier = true;
  wall.observations.push_back(seen);
  GlobalPlane floor;
  floor.id = 1;
  floor.normal_world = Eigen::Vector3d(0, 0, 1);
  floor.distance_world = 0.0;
  map.planes = {wall, floor};
  return map;
}

TEST(PlanesJson, WrittenAndReadBackIsTheSameMap) {
  test::TempDir dir;
  const std::string path = (dir.path() / "planes.json").string();
  writePlanesJson(path, sampleMap());
  const PlaneMap read = readPlanesJson(path);
  EXPECT_EQ(read.keyframes, 3);
  ASSERT_EQ(read.planes.size(), 2u);
  const GlobalPlane& wall = read.planes[0];
  EXPECT_EQ(wall.normal_world, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(wall.distance_world, 2.0);
  ASSERT_TRUE(wall.facing_world);
  EXPECT_EQ(*wall.facing_world, Eigen::Vector3d(-1, 0, 0));
  ASSERT_EQ(wall.observations.size(), 1u);
  const PlaneObservation& o = wall.observations[0];
  EXPECT_EQ(o.keyframe, 2);
  ASSERT_TRUE(o.time);
  EXPECT_EQ(*o.time, 12.25);
  EXPECT_EQ(o.normal_keyframe, Eigen::Vector3d(0, -1, 0));
  EXPECT_EQ(o.distance_keyframe, 1.9375);
  ASSERT_TRUE(o.centroid_keyframe);
  EXPECT_EQ(*o.centroid_keyframe, Eigen::Vector3d(0.5, -1.9375, 0.25));
  ASSERT_EQ(o.hull_keyframe.size(), 3u);
  EXPECT_EQ(o.hull_keyframe[2], Eigen::Vector3d(3, -1.9375, 1));
  EXPECT_EQ(o.points, 512);
  EXPECT_EQ(o.fit_rms, 0.0125);
  EXPECT_EQ(o.residual_chi2, 7.5);
  EXPECT_TRUE(o.outlier);
  EXPECT_FALSE(read.planes[1].facing_world);
  EXPECT_TRUE(read.planes[1].observations.empty());
  // The text is a fixed point: written again it is the same bytes.
  EXPECT_EQ(planesJsonText(read), planesJsonText(sampleMap()));
}

TEST(PlanesJson, OlderFilesWithoutOptionalFields) {
  const PlaneMap map = parsePlanesJson(R"({"planes": [
      {"normal": [0, 0, 1], "distance": 2.5, "observations": [
        {"keyframe": 0, "normal": [0, 0, 1], "distance": 2.5}]}]})",
                                       "old.json");
  ASSERT_EQ(map.planes.size(), 1u);
  EXPECT_EQ(map.planes[0].id, 0);  // its index
  EXPECT_FALSE(map.planes[0].facing_world);
  const PlaneObservation& o = map.planes[0].observations[0];
  EXPECT_FALSE(o.time);
  EXPECT_FALSE(o.centroid_keyframe);
  EXPECT_TRUE(o.hull_keyframe.empty());
  EXPECT_EQ(o.points, 0);
  EXPECT_FALSE(o.outlier);
}

TEST(PlanesJson, ErrorsNameTheSourceAndThePlace) {
  auto message = [](const std::string& text) {
    try {
      parsePlanesJson(text, "p.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("{"), "p.json: not a JSON object");
  EXPECT_EQ(message(R"({"planes": 3})"),
            "p.json: no 'planes' array (not a planes.json of storey run)");
  EXPECT_EQ(message(R"({"planes": [{"id": 0, "normal": [1, 0], "distance": 1}]})"),
            "p.json: planes[0].normal: expected [x, y, z]");
  EXPECT_EQ(message(R"({"planes": [{"normal": [1, 0, 0], "distance": 1,
                                    "observations": [{"normal": [1, 0, 0], "distance": 1}]}]})"),
            "p.json: planes[0].observations[0]: 'keyframe' missing or not an integer");
  EXPECT_EQ(message(R"({"planes": [{"normal": [1, 0, 0], "distance": 1,
                                    "observations": [{"keyframe": 0, "normal": [1, 0, 0],
                                                      "distance": 1, "outlier": 1}]}]})"),
            "p.json: planes[0].observations[0]: 'outlier' is not true or false");
  EXPECT_THROW(readPlanesJson("/nonexistent/planes.json"), Error);
}

}  // namespace
}  // namespace storey
