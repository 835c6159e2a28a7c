#include "sim/mesh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <ostream>

#include "common/atomic_file.h"
#include "common/error.h"

namespace storey::sim {

const char* toString(Surface surface) {
  switch (surface) {
    case Surface::kFloor:
      return "floor";
    case Surface::kCeiling:
      return "ceiling";
    case Surface::kWall:
      return "wall";
    case Surface::kStairs:
      return "stairs";
    case Surface::kClutter:
      return "clutter";
    case Surface::kPillar:
      return "pillar";
    case Surface::kGlass:
      return "glass";
    case Surface::kDoorFrame:
      return "door_frame";
  }
  return "unknown";
}

float surfaceReflectivity(Surface surface) {
  switch (surface) {
    case Surface::kFloor:
      return 25.0f;
    case Surface::kCeiling:
      return 70.0f;
    case Surface::kWall:
      return 55.0f;
    case Surface::kStairs:
      return 35.0f;
    case Surface::kClutter:
      return 40.0f;
    case Surface::kPillar:
      return 60.0f;
    case Surface::kGlass:
      return 0.0f;
    case Surface::kDoorFrame:
      return 90.0f;
  }
  return 40.0f;
}

std::uint32_t TriangleMesh::addVertex(const Eigen::Vector3d& v) {
  vertices_.push_back(v);
  return static_cast<std::uint32_t>(vertices_.size() - 1);
}

void TriangleMesh::addQuad(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, const Eigen::Vector3d& d, Surface surface,
                           float reflectivity) {
  const std::uint32_t ia = addVertex(a), ib = addVertex(b), ic = addVertex(c), id = addVertex(d);
  triangles_.push_back({{ia, ib, ic}, surface, reflectivity});
  triangles_.push_back({{ia, ic, id}, surface, reflectivity});
}

void TriangleMesh::addBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Surface surface,
                          float reflectivity) {
  if (!((hi - lo).array() > 1e-6).all()) return;
  const double x0 = lo.x(), y0 = lo.y(), z0 = lo.z(), x1 = hi.x(), y1 = hi.y(), z1 = hi.z();
  const std::uint32_t base = static_cast<std::uint32_t>(vertices_.size());
  for (int i = 0; i < 8; ++i)
    vertices_.emplace_back((i & 1) ? x1 : x0, (i & 2) ? y1 : y0, (i & 4) ? z1 : z0);
  // Faces as corner index quads, counter-clockwise seen from outside.
  static const int kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : kFaces) {
    triangles_.push_back({{base + f[0], base + f[1], base + f[2]}, surface, reflectivity});
    triangles_.push_back({{base + f[0], base + f[2], base + f[3]}, surface, reflectivity});
  }
}

void TriangleMesh::addPrism(const std::array<Eigen::Vector2d, 4>& footprint, double z0, double z1,
                            Surface surface, float reflectivity) {
  if (z1 - z0 < 1e-6) return;
  const std::uint32_t base = static_cast<std::uint32_t>(vertices_.size());
  for (double z : {z0, z1})
    for (const Eigen::Vector2d& p : footprint) vertices_.emplace_back(p.x(), p.y(), z);
  auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    triangles_.push_back({{base + a, base + b, base + c}, surface, reflectivity});
    triangles_.push_back({{base + a, base + c, base + d}, surface, reflectivity});
  };
  quad(0, 3, 2, 1);  // bottom, seen from below
  quad(4, 5, 6, 7);  // top
  for (std::uint32_t i = 0; i < 4; ++i) {
    const std::uint32_t j = (i + 1) % 4;
    quad(i, j, 4 + j, 4 + i);
  }
}

void TriangleMesh::addCylinder(const Eigen::Vector2d& centre, double radius, double z0, double z1,
                               int sides, Surface surface, float reflectivity) {
  const std::uint32_t base = static_cast<std::uint32_t>(vertices_.size());
  for (int i = 0; i < sides; ++i) {
    const double a = 2.0 * M_PI * i / sides;
    const Eigen::Vector2d p = centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a));
    vertices_.emplace_back(p.x(), p.y(), z0);
    vertices_.emplace_back(p.x(), p.y(), z1);
  }
  const std::uint32_t bottom = addVertex(Eigen::Vector3d(centre.x(), centre.y(), z0));
  const std::uint32_t top = addVertex(Eigen::Vector3d(centre.x(), centre.y(), z1));
  const std::uint32_t n = static_cast<std::uint32_t>(sides);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    const std::uint32_t b0 = base + 2 * i, t0 = b0 + 1, b1 = base + 2 * j, t1 = b1 + 1;
    triangles_.push_back({{b0, b1, t1}, surface, reflectivity});
    triangles_.push_back({{b0, t1, t0}, surface, reflectivity});
    triangles_.push_back({{bottom, b1, b0}, surface, reflectivity});
    triangles_.push_back({{top, t0, t1}, surface, reflectivity});
  }
}

void TriangleMesh::translate(const Eigen::Vector3d& offset) {
  for (Eigen::Vector3d& v : vertices_) v += offset;
}

void TriangleMesh::append(const TriangleMesh& other, const Eigen::Matrix3d& R,
                          const Eigen::Vector3d& t) {
  const auto base = static_cast<std::uint32_t>(vertices_.size());
  vertices_.reserve(vertices_.size() + other.vertices_.size());
  for (const Eigen::Vector3d& v : other.vertices_) vertices_.push_back(R * v + t);
  triangles_.reserve(triangles_.size() + other.triangles_.size());
  for (Triangle tri : other.triangles_) {
    for (std::uint32_t& index : tri.v) index += base;
    triangles_.push_back(tri);
  }
}

void TriangleMesh::rotateZ(double yaw) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (Eigen::Vector3d& v : vertices_) v = R * v;
}

double pointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Ericson, Real-Time Collision Detection, closest point on triangle.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

double TriangleMesh::distanceTo(const Eigen::Vector3d& x, bool returning_only) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Triangle& t : triangles_) {
    if (returning_only && !returnsLight(t.surface)) continue;
    best = std::min(
        best, pointTriangleDistance(x, vertices_[t.v[0]], vertices_[t.v[1]], vertices_[t.v[2]]));
  }
  return best;
}

namespace {
template <typename T>
void put(std::ostream& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // little-endian host (x86-64, aarch64)
  out.write(bytes, sizeof(T));
}
}  // namespace

void TriangleMesh::writePly(const std::string& path) const {
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\n"
        << "comment Storey simulated building; world frame (z up, origin at the LiDAR start)\n"
        << "comment surface: 0 floor 1 ceiling 2 wall 3 stairs 4 clutter 5 pillar 6 glass 7 "
           "door_frame\n"
        << "comment returns: 0 = the simulated LiDAR sees through this face (glass)\n"
        << "element vertex " << vertices_.size() << "\n"
        << "property double x\nproperty double y\nproperty double z\n"
        << "element face " << triangles_.size() << "\n"
        << "property list uchar int vertex_indices\n"
        << "property uchar surface\nproperty uchar returns\nproperty float reflectivity\n"
        << "end_header\n";
    for (const Eigen::Vector3d& v : vertices_) {
      put(out, v.x());
      put(out, v.y());
      put(out, v.z());
    }
    for (const Triangle& t : triangles_) {
      put<std::uint8_t>(out, 3);
      for (std::uint32_t i : t.v) put<std::int32_t>(out, static_cast<std::int32_t>(i));
      put<std::uint8_t>(out, static_cast<std::uint8_t>(t.surface));
      put<std::uint8_t>(out, returnsLight(t.surface) ? 1 : 0);
      put<float>(out, t.reflectivity);
    }
  });
}

}  // namespace storey::sim
