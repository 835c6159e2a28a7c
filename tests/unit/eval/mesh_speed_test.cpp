// Speed of the map-to-mesh evaluation on a realistic map: points sampled on
// the simulated building's surfaces with 1 cm noise, written as a binary PLY
// and evaluated from the files. Disabled by default (it writes ~50 MB); run
// with --gtest_also_run_disabled_tests --gtest_filter='*Speed*'.
// STOREY_EVAL_SPEED_POINTS sets the point count (default 2,000,000).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "eval/evaluation.h"
#include "sim/building.h"
#include "sim/building_spec.h"
#include "unit/eval/eval_fixtures.h"

namespace storey::eval {
namespace {

TEST(EvalMapSpeed, DISABLED_MillionsOfPointsAgainstTheBuildingMesh) {
  const char* env = std::getenv("STOREY_EVAL_SPEED_POINTS");
  const std::size_t n = env ? std::strtoull(env, nullptr, 10) : 2000000;
  const sim::Building building = sim::generateBuilding(sim::loadBuildingSpec("building-a"));
  const std::string dir = test::eval::makeTempDir("speed");
  building.mesh.writePly(dir + "/building.ply");

  // Area-weighted sampling of the returning triangles.
  const auto& v = building.mesh.vertices();
  std::vector<const sim::Triangle*> faces;
  std::vector<double> area;
  for (const sim::Triangle& t : building.mesh.triangles()) {
    if (!sim::returnsLight(t.surface)) continue;
    faces.push_back(&t);
    area.push_back(0.5 * (v[t.v[1]] - v[t.v[0]]).cross(v[t.v[2]] - v[t.v[0]]).norm());
  }
  std::mt19937 rng(3);
  std::discrete_distribution<std::size_t> pick(area.begin(), area.end());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  {
    std::ofstream out(dir + "/map.ply", std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << n
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\n"
           "property uchar storey\nend_header\n";
    for (std::size_t i = 0; i < n; ++i) {
      const sim::Triangle& t = *faces[pick(rng)];
      double a = u(rng), b = u(rng);
      if (a + b > 1.0) {
        a = 1.0 - a;
        b = 1.0 - b;
      }
      const Eigen::Vector3d p = v[t.v[0]] + a * (v[t.v[1]] - v[t.v[0]]) +
                                b * (v[t.v[2]] - v[t.v[0]]) +
                                Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      char record[17];
      for (int k = 0; k < 3; ++k) {
        const float f = static_cast<float>(p[k]);
        std::memcpy(record + 4 * k, &f, 4);
      }
      const float intensity = 40.0f;
      std::memcpy(record + 12, &intensity, 4);
      record[16] = 0;
      out.write(record, sizeof(record));
    }
  }
  const MapEvaluation m = evaluateMap(dir + "/building.ply", dir + "/map.ply");
  std::cout << "[ speed    ] " << m.points << " points, " << m.triangles << " triangles: read "
            << m.read_seconds << " s, tree " << m.build_seconds << " s, queries " << m.query_seconds
            << " s = " << m.points / m.query_seconds << " points/s; median " << m.distance.median
            << " m, p95 " << m.distance.p95 << " m\n";
  EXPECT_EQ(m.points, n);
  EXPECT_LT(m.distance.median, 0.02);  // 1 cm noise per axis
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace storey::eval
