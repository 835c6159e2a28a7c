// Point-to-mesh distance with CGAL's AABB tree, against hand-made meshes with
// known answers and against the simulator's brute-force distance.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <random>

#include "common/error.h"
#include "eval/mesh_distance.h"
#include "sim/building.h"
#include "sim/building_spec.h"

namespace storey::eval {
namespace {

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

/// The unit cube [0, 1]^3 as 12 triangles.
void unitCube(std::vector<Eigen::Vector3d>& vertices, Triangles& triangles) {
  vertices.clear();
  for (int i = 0; i < 8; ++i) vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  triangles.clear();
  for (const auto& q : quads) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  }
}

TEST(EvalMeshDistance, UnitCubeGivesTheOffsetsOfPointsPlacedAroundIt) {
  std::vector<Eigen::Vector3d> vertices;
  Triangles triangles;
  unitCube(vertices, triangles);
  const MeshDistance mesh(vertices, triangles);
  EXPECT_EQ(mesh.triangles(), 12u);
  const std::vector<std::pair<Eigen::Vector3d, double>> cases = {
      {{0.5, 0.5, 1.3}, 0.3},             // above the top face
      {{0.25, 0.75, -0.02}, 0.02},        // below the bottom face
      {{-0.07, 0.5, 0.5}, 0.07},          // beside a side face
      {{1.3, 1.4, 0.5}, 0.5},             // off a vertical edge: |(0.3, 0.4)|
      {{2.0, 2.0, 2.0}, std::sqrt(3.0)},  // off a corner
      {{0.5, 0.5, 0.4}, 0.4},             // inside: to the nearest face (unsigned)
      {{0.3, 0.0, 0.6}, 0.0},             // on a face
  };
  std::vector<Eigen::Vector3d> points;
  for (const auto& [p, expected] : cases) {
    EXPECT_NEAR(mesh.distance(p), expected, 1e-12) << p.transpose();
    points.push_back(p);
  }
  const std::vector<double> parallel = mesh.distances(points, 2);
  ASSERT_EQ(parallel.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) EXPECT_NEAR(parallel[i], cases[i].second, 1e-12);
}

TEST(EvalMeshDistance, TwoTrianglesOfASquare) {
  const std::vector<Eigen::Vector3d> vertices = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  const MeshDistance mesh(vertices, {{0, 1, 2}, {0, 2, 3}});
  for (double h : {-0.05, 0.01, 0.5, 3.0})
    EXPECT_NEAR(mesh.distance(Eigen::Vector3d(1.3, 0.4, h)), std::abs(h), 1e-12);
  EXPECT_NEAR(mesh.distance(Eigen::Vector3d(-0.3, 1.0, 0.4)), 0.5, 1e-12);
}

TEST(EvalMeshDistance, DegenerateMeshesAreErrors) {
  const std::vector<Eigen::Vector3d> vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_THROW(MeshDistance(vertices, {{0, 1, 2}}), Error);  // collinear
  EXPECT_THROW(MeshDistance(vertices, {{0, 1, 3}}), Error);  // missing vertex
}

// The simulator's building: the tree agrees with the brute-force distance
// (sim::TriangleMesh::distanceTo), and the rate is printed for the record.
TEST(EvalMeshDistance, AgreesWithBruteForceOnTheSimulatedBuilding) {
  const sim::Building building = sim::generateBuilding(sim::loadBuildingSpec("default"));
  std::vector<Eigen::Vector3d> vertices = building.mesh.vertices();
  Triangles triangles;
  for (const sim::Triangle& t : building.mesh.triangles())
    if (sim::returnsLight(t.surface)) triangles.push_back({t.v[0], t.v[1], t.v[2]});
  const MeshDistance mesh(vertices, triangles);

  Eigen::Vector3d lo = vertices.front(), hi = vertices.front();
  for (const Eigen::Vector3d& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> points(200000);
  for (Eigen::Vector3d& p : points)
    p = lo + Eigen::Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(hi - lo);

  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> d = mesh.distances(points, 0);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ rate     ] " << points.size() << " points, " << mesh.triangles()
            << " triangles: " << seconds << " s, " << points.size() / seconds << " points/s\n";
  for (std::size_t i = 0; i < points.size(); i += 2000)
    EXPECT_NEAR(d[i], building.mesh.distanceTo(points[i]), 1e-9) << i;
}

}  // namespace
}  // namespace storey::eval
