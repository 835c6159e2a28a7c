#include "render/srp_patches.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "backend/plane_hull.h"
#include "common/parallel_chunks.h"

namespace storey::render {
namespace {

struct CellKey {
  int x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return static_cast<std::size_t>(k.x) * 73856093u ^ static_cast<std::size_t>(k.y) * 19349663u ^
           static_cast<std::size_t>(k.z) * 83492791u;
  }
};

/// Hull in plane coordinates plus the plane, for fast inside tests.
struct FlatPatch {
  Eigen::Vector3d n, u, v, origin;
  double d = 0.0;
  std::vector<Eigen::Vector2d> polygon;  ///< counter-clockwise
  Eigen::AlignedBox3d box;
  int plane_id = 0;
};

FlatPatch flatten(const WorldPatch& p, double margin) {
  FlatPatch f;
  f.n = p.normal;
  f.d = p.distance;
  planeBasis(f.n, f.u, f.v);
  f.origin = f.n * f.d;
  std::vector<Eigen::Vector2d> pts;
  for (const auto& h : p.hull) {
    pts.emplace_back((h - f.origin).dot(f.u), (h - f.origin).dot(f.v));
    f.box.extend(h);
  }
  f.polygon = backend::convexHull(pts);
  f.box.min().array() -= margin;
  f.box.max().array() += margin;
  f.plane_id = p.plane_id;
  return f;
}

bool inside(const FlatPatch& f, const Eigen::Vector3d& p, double distance) {
  if (!f.box.contains(p)) return false;
  if (std::abs(f.n.dot(p) - f.d) > distance) return false;
  const Eigen::Vector2d q((p - f.origin).dot(f.u), (p - f.origin).dot(f.v));
  const std::size_t n = f.polygon.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = f.polygon[i], b = f.polygon[(i + 1) % n];
    const double cross = (b.x() - a.x()) * (q.y() - a.y()) - (b.y() - a.y()) * (q.x() - a.x());
    if (cross < -1e-9) return false;
  }
  return true;
}

}  // namespace

void planeBasis(const Eigen::Vector3d& n, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d a =
      std::abs(n.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  u = n.cross(a).normalized();
  v = n.cross(u).normalized();
}

PatchSet worldPatches(const RunData& run, double point_distance, double fallback_radius) {
  PatchSet out;
  // For patches estimated from the map: map points bucketed in cells of the search radius.
  struct Key3 {
    int x, y, z;
    bool operator==(const Key3& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash3 {
    std::size_t operator()(const Key3& k) const {
      return static_cast<std::size_t>(k.x) * 73856093u ^ static_cast<std::size_t>(k.y) * 19349663u ^
             static_cast<std::size_t>(k.z) * 83492791u;
    }
  };
  std::unordered_map<Key3, std::vector<std::uint32_t>, Hash3> buckets;
  auto key = [&](const Eigen::Vector3d& q) {
    return Key3{static_cast<int>(std::floor(q.x() / fallback_radius)),
                static_cast<int>(std::floor(q.y() / fallback_radius)),
                static_cast<int>(std::floor(q.z() / fallback_radius))};
  };
  bool need_buckets = false;
  for (const GlobalPlane& plane : run.planes)
    for (const PlaneObservation& o : plane.observations) need_buckets |= o.hull_keyframe.size() < 3;
  if (need_buckets) {
    for (std::size_t i = 0; i < run.map.size(); ++i)
      buckets[key(run.map.positions[i].cast<double>())].push_back(static_cast<std::uint32_t>(i));
  }
  for (std::size_t pi = 0; pi < run.planes.size(); ++pi) {
    const GlobalPlane& plane = run.planes[pi];
    for (std::size_t oi = 0; oi < plane.observations.size(); ++oi) {
      const PlaneObservation& o = plane.observations[oi];
      if (o.keyframe < 0 || o.keyframe >= static_cast<int>(run.keyframes.size())) {
        ++out.skipped;
        continue;
      }
      const Pose& T_world_lidar = run.keyframes[static_cast<std::size_t>(o.keyframe)].pose;
      WorldPatch p;
      p.plane_id = plane.id;
      p.plane_index = static_cast<int>(pi);
      p.keyframe = o.keyframe;
      p.observation = static_cast<int>(oi);
      p.normal = (T_world_lidar.rotationMatrix() * o.normal_keyframe).normalized();
      p.distance = o.distance_keyframe + p.normal.dot(T_world_lidar.translation());
      // Seen side: towards the sensor of this observation.
      const double side = p.normal.dot(T_world_lidar.translation()) - p.distance;
      p.facing = side >= 0.0 ? p.normal : Eigen::Vector3d(-p.normal);
      Eigen::Vector3d u, v;
      planeBasis(p.normal, u, v);
      const Eigen::Vector3d origin = p.normal * p.distance;
      std::vector<Eigen::Vector2d> flat;
      if (o.hull_keyframe.size() >= 3) {
        for (const auto& h : o.hull_keyframe) {
          const Eigen::Vector3d w = T_world_lidar * h;
          flat.emplace_back((w - origin).dot(u), (w - origin).dot(v));
        }
      } else {
        // Estimated from the map: points on the observed plane near the keyframe.
        const Eigen::Vector3d at = T_world_lidar.translation();
        const Key3 c = key(at);
        for (int dx = -1; dx <= 1; ++dx)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
              const auto it = buckets.find({c.x + dx, c.y + dy, c.z + dz});
              if (it == buckets.end()) continue;
              for (std::uint32_t i : it->second) {
                const Eigen::Vector3d q = run.map.positions[i].cast<double>();
                if ((q - at).squaredNorm() > fallback_radius * fallback_radius) continue;
                if (std::abs(p.normal.dot(q) - p.distance) > point_distance) continue;
                flat.emplace_back((q - origin).dot(u), (q - origin).dot(v));
              }
            }
        p.estimated = true;
      }
      const std::vector<Eigen::Vector2d> hull = backend::convexHull(flat);
      if (hull.size() < 3) {
        ++out.skipped;
        continue;
      }
      if (p.estimated) ++out.estimated;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const auto& h : hull) {
        p.hull.push_back(origin + h.x() * u + h.y() * v);
        sum += p.hull.back();
      }
      p.centroid = sum / static_cast<double>(p.hull.size());
      out.patches.push_back(std::move(p));
    }
  }
  return out;
}

std::vector<int> srpOfPoints(const MapSample& map, const std::vector<WorldPatch>& patches,
                             double point_distance, const std::vector<int>& use) {
  std::vector<int> out(map.size(), -1);
  std::vector<FlatPatch> flat;
  if (use.empty()) {
    for (const auto& p : patches) flat.push_back(flatten(p, point_distance));
  } else {
    for (int i : use) flat.push_back(flatten(patches[static_cast<std::size_t>(i)], point_distance));
  }
  if (flat.empty()) return out;
  // The patches whose box reaches each 1 m cube, in patch order: a point's
  // first containing patch is the first of its cube's list that contains it
  // (cubes, not columns: the storeys' floors and their observations, stacked
  // in a column, would all be tested).
  constexpr double kCell = 1.0;
  const auto cell = [](double c) { return static_cast<int>(std::floor(c / kCell)); };
  std::unordered_map<CellKey, std::vector<int>, CellHash> grid;
  for (std::size_t i = 0; i < flat.size(); ++i) {
    const auto& b = flat[i].box;
    for (int x = cell(b.min().x()); x <= cell(b.max().x()); ++x)
      for (int y = cell(b.min().y()); y <= cell(b.max().y()); ++y)
        for (int z = cell(b.min().z()); z <= cell(b.max().z()); ++z)
          grid[{x, y, z}].push_back(static_cast<int>(i));
  }
  // Each point on its own: in chunks on every core.
  constexpr std::size_t kChunk = 1 << 15;
  const ParallelChunks parallel(0);
  parallel.run((map.size() + kChunk - 1) / kChunk, [&](std::size_t c) {
    for (std::size_t i = c * kChunk; i < std::min(map.size(), (c + 1) * kChunk); ++i) {
      const Eigen::Vector3d p = map.positions[i].cast<double>();
      const auto it = grid.find({cell(p.x()), cell(p.y()), cell(p.z())});
      if (it == grid.end()) continue;
      for (int k : it->second) {
        if (inside(flat[static_cast<std::size_t>(k)], p, point_distance)) {
          out[i] = flat[static_cast<std::size_t>(k)].plane_id;
          break;
        }
      }
    }
  });
  return out;
}

}  // namespace storey::render
