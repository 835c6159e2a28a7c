#pragma once
/// Triangle mesh of the simulated building, with a surface class per
/// triangle (what the LiDAR sees: reflectivity, and whether it returns at all).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace storey::sim {

/// What a triangle is made of. Glass returns nothing: rays pass through it.
enum class Surface : std::uint8_t {
  kFloor = 0,
  kCeiling = 1,
  kWall = 2,
  kStairs = 3,
  kClutter = 4,
  kPillar = 5,
  kGlass = 6,
  kDoorFrame = 7,
};
const char* toString(Surface surface);
/// Diffuse reflectivity reported as VLP-16 calibrated intensity [0, 255] at normal incidence.
float surfaceReflectivity(Surface surface);
inline bool returnsLight(Surface surface) {
  return surface != Surface::kGlass;
}

struct Triangle {
  std::uint32_t v[3];  ///< vertex indices, counter-clockwise seen from outside
  Surface surface;
  float reflectivity;  ///< [0, 255]
};

class TriangleMesh {
 public:
  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }

  /// Axis-aligned box [lo, hi] (12 triangles, outward normals). Degenerate boxes are skipped.
  void addBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Surface surface,
              float reflectivity);
  void addBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Surface surface) {
    addBox(lo, hi, surface, surfaceReflectivity(surface));
  }
  /// Vertical cylinder (a prism with `sides` faces) from z0 to z1.
  void addCylinder(const Eigen::Vector2d& centre, double radius, double z0, double z1, int sides,
                   Surface surface, float reflectivity);
  /// A planar quad a-b-c-d (two triangles).
  void addQuad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
               const Eigen::Vector3d& d, Surface surface, float reflectivity);
  /// Vertical prism over a convex quadrilateral (corners counter-clockwise
  /// seen from above) from z0 to z1: 12 triangles, outward normals.
  void addPrism(const std::array<Eigen::Vector2d, 4>& footprint, double z0, double z1,
                Surface surface, float reflectivity);
  void translate(const Eigen::Vector3d& offset);
  /// Adds the triangles of `other`, each vertex moved to R v + t.
  void append(const TriangleMesh& other, const Eigen::Matrix3d& R, const Eigen::Vector3d& t);
  /// Turns every vertex about the world z axis through the origin by `yaw` [rad].
  void rotateZ(double yaw);

  /// Unsigned distance from x to the nearest triangle of a returning surface
  /// (brute force; for tests and checks, not per point in production).
  double distanceTo(const Eigen::Vector3d& x, bool returning_only = true) const;

  /// Binary little-endian PLY: vertex x y z (float64), face vertex_indices
  /// (uint8 count, int32 indices), surface (uint8, see Surface), returns
  /// (uint8 0/1), reflectivity (float32). Written atomically.
  void writePly(const std::string& path) const;

 private:
  std::uint32_t addVertex(const Eigen::Vector3d& v);
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Triangle> triangles_;
};

/// Distance from point p to triangle (a, b, c).
double pointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace storey::sim
