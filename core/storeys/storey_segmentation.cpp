#include "storeys/storey_segmentation.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "common/error.h"
#include "types/voxel_hash.h"

namespace storey {

namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  return values[mid];
}

/// Key of a 2D grid cell.
std::uint64_t cellKey(double x, double y, double inverse_size) {
  return packVoxel(static_cast<std::int64_t>(std::floor(x * inverse_size)),
                   static_cast<std::int64_t>(std::floor(y * inverse_size)), 0);
}

/// The map subsampled for plane detection: voxel centroids and the keyframe
/// of each voxel's first point.
struct Subsample {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::int32_t> keyframe;
};

Subsample subsample(const MapCloud& map, double voxel_size) {
  const double inv = 1.0 / voxel_size;
  VoxelIndex index(map.size() / 8 + 1024);
  Subsample s;
  std::vector<std::uint32_t> counts;
  for (std::size_t i = 0; i < map.size(); ++i) {
    const Eigen::Vector3d p = map.positions[i].cast<double>();
    if (!p.allFinite()) continue;
    bool inserted = false;
    const std::uint32_t v = index.findOrInsert(voxelKey(p, inv), inserted);
    if (inserted) {
      s.points.push_back(p);
      s.keyframe.push_back(map.keyframe[i]);
      counts.push_back(1);
    } else {
      s.points[v] += p;
      ++counts[v];
    }
  }
  for (std::size_t v = 0; v < s.points.size(); ++v) s.points[v] /= static_cast<double>(counts[v]);
  return s;
}

/// A horizontal region (floor or ceiling candidate).
struct HorizontalRegion {
  std::size_t region = 0;  ///< index into the regions
  double elevation = 0.0;  ///< median z [m]
  double area = 0.0;       ///< occupied xy cells x cell area [m^2]
};

/// Regions clustered by elevation.
struct Slab {
  std::vector<std::size_t> members;  ///< indices into the candidate list
  double elevation = 0.0;            ///< median z of all member points [m]
  double area = 0.0;                 ///< occupied xy cells [m^2]
};

/// Calls fn(i) for the index of every subsampled point of a slab's regions.
template <typename Fn>
void forEachSlabPoint(const Slab& slab, const std::vector<HorizontalRegion>& candidates,
                      const std::vector<PlanarRegion>& regions, Fn&& fn) {
  for (std::size_t c : slab.members)
    for (std::size_t i : regions[candidates[c].region].indices) fn(i);
}

double cellArea(const std::vector<std::size_t>& point_indices,
                const std::vector<Eigen::Vector3d>& points, double cell) {
  std::unordered_set<std::uint64_t> cells;
  cells.reserve(point_indices.size());
  const double inv = 1.0 / cell;
  for (std::size_t i : point_indices) cells.insert(cellKey(points[i].x(), points[i].y(), inv));
  return static_cast<double>(cells.size()) * cell * cell;
}

std::vector<Slab> clusterByElevation(const std::vector<HorizontalRegion>& candidates,
                                     const std::vector<PlanarRegion>& regions,
                                     const std::vector<Eigen::Vector3d>& points, double tolerance,
                                     double cell) {
  std::vector<std::size_t> order(candidates.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return candidates[a].elevation < candidates[b].elevation;
  });
  std::vector<Slab> slabs;
  for (std::size_t c : order) {
    if (slabs.empty() ||
        candidates[c].elevation - candidates[slabs.back().members.back()].elevation > tolerance)
      slabs.emplace_back();
    slabs.back().members.push_back(c);
  }
  for (Slab& slab : slabs) {
    std::vector<double> z;
    std::vector<std::size_t> all;
    forEachSlabPoint(slab, candidates, regions, [&](std::size_t i) {
      z.push_back(points[i].z());
      all.push_back(i);
    });
    slab.elevation = median(std::move(z));
    slab.area = cellArea(all, points, cell);
  }
  return slabs;
}

/// Flights: runs of steep keyframe-to-keyframe steps (slope >= kStairSlope,
/// rising or falling) climbing at least kMinFlightRise in total. A ramp
/// (buildings: <= 1:12) is never steep; the few steps up to a split level
/// climb less than a flight.
constexpr double kStairSlope = 0.3;       // 17 deg; stairs are 25-40 deg, ramps <= 5 deg
constexpr double kMinStepRise = 0.05;     // [m] smaller steps are noise, not stairs
constexpr double kMinFlightRise = 1.0;    // [m] half a storey's flight and more
constexpr double kArrivalReach = 1.0;     // [m] a floor slab this close (xy) carries a flight end
constexpr double kMinSensorHeight = 0.2;  // [m] the sensor above the floor it stands on ...
constexpr double kMaxSensorHeight = 2.5;  // ... at most this
constexpr double kStandTolerance = 0.25;  // [m] a flight end's floor: this close to one usual
                                          // sensor height below it (gait, a riser and a half)

/// Whether the step from keyframe k to k + 1 is steep.
bool steepStep(const std::vector<Eigen::Vector3d>& keyframes, std::size_t k) {
  const Eigen::Vector3d& a = keyframes[k];
  const Eigen::Vector3d& b = keyframes[k + 1];
  if (!a.allFinite() || !b.allFinite()) return false;
  const double dz = std::abs(b.z() - a.z());
  return dz >= kMinStepRise && dz >= kStairSlope * (b - a).head<2>().norm();
}

/// Where the walker stands at each end of every flight: of the flight's end
/// keyframe and its level neighbour outside the flight (keyframes are about a
/// metre of path apart, so the end keyframe may still be a riser or two below
/// the top or above the bottom), the higher at the upper end, the lower at the
/// lower end.
std::vector<Eigen::Vector3d> flightEnds(const std::vector<Eigen::Vector3d>& keyframes) {
  auto standing = [&](std::size_t end, std::size_t neighbour, bool upper) {
    const Eigen::Vector3d& e = keyframes[end];
    if (neighbour >= keyframes.size() || !keyframes[neighbour].allFinite()) return e;
    const Eigen::Vector3d& n = keyframes[neighbour];
    return (upper ? n.z() > e.z() : n.z() < e.z()) ? n : e;
  };
  std::vector<Eigen::Vector3d> ends;
  std::size_t i = 0;
  while (i + 1 < keyframes.size()) {
    if (!steepStep(keyframes, i)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < keyframes.size() && steepStep(keyframes, j)) ++j;
    const double climb = keyframes[j].z() - keyframes[i].z();
    if (std::abs(climb) >= kMinFlightRise) {
      const std::size_t before = i > 0 ? i - 1 : keyframes.size();  // none: the end itself
      ends.push_back(standing(i, before, climb < 0.0));
      ends.push_back(standing(j, j + 1, climb > 0.0));
    }
    i = j;
  }
  return ends;
}

/// Per floor slab: how many flight ends stand on it. Stairs arrive at a
/// storey's main floor. A walker stands one usual sensor height above the
/// floor (the median over the keyframes off the stairs of the height above
/// the highest slab right below them); a flight end votes for the slab, among
/// those with points within kArrivalReach in xy and kMinSensorHeight to
/// kMaxSensorHeight below the sensor, nearest to that height below it (within
/// kStandTolerance). The highest such slab would be a split level's wing next
/// to the landing, or a stair tread at the wing's elevation, wherever the
/// sensor is carried higher above the floor than the wing's rise.
std::vector<std::size_t> flightEndVotes(const std::vector<Slab>& slabs,
                                        const std::vector<HorizontalRegion>& candidates,
                                        const std::vector<PlanarRegion>& regions,
                                        const std::vector<Eigen::Vector3d>& points,
                                        const std::vector<Eigen::Vector3d>& keyframes,
                                        StoreySegmentationStats& stats) {
  std::vector<std::size_t> votes(slabs.size(), 0);
  const std::vector<Eigen::Vector3d> ends = flightEnds(keyframes);
  stats.flight_ends = ends.size();
  if (ends.empty()) return votes;
  const double cell = 0.5 * kArrivalReach, inv = 1.0 / cell;
  std::vector<std::unordered_set<std::uint64_t>> cells(slabs.size());
  for (std::size_t s = 0; s < slabs.size(); ++s)
    forEachSlabPoint(slabs[s], candidates, regions, [&](std::size_t i) {
      cells[s].insert(cellKey(points[i].x(), points[i].y(), inv));
    });
  // Slabs with points within `reach` cells (xy) and a sensor height below `sensor`.
  auto slabsBelow = [&](const Eigen::Vector3d& sensor, int reach) {
    std::vector<std::size_t> below;
    for (std::size_t s = 0; s < slabs.size(); ++s) {
      const double height = sensor.z() - slabs[s].elevation;
      if (height < kMinSensorHeight || height > kMaxSensorHeight) continue;
      bool near = false;
      for (int dx = -reach; dx <= reach && !near; ++dx)
        for (int dy = -reach; dy <= reach && !near; ++dy)
          near = cells[s].count(cellKey(sensor.x() + dx * cell, sensor.y() + dy * cell, inv)) > 0;
      if (near) below.push_back(s);
    }
    return below;
  };
  std::vector<double> heights;
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    if (!keyframes[k].allFinite()) continue;
    if ((k > 0 && steepStep(keyframes, k - 1)) ||
        (k + 1 < keyframes.size() && steepStep(keyframes, k)))
      continue;
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t s : slabsBelow(keyframes[k], 1)) top = std::max(top, slabs[s].elevation);
    if (std::isfinite(top)) heights.push_back(keyframes[k].z() - top);
  }
  if (heights.empty()) return votes;
  const double usual = median(std::move(heights));
  stats.usual_sensor_height = usual;
  for (const Eigen::Vector3d& end : ends) {
    std::size_t best = slabs.size();
    double best_offset = kStandTolerance;
    for (std::size_t s : slabsBelow(end, 2)) {
      const double offset = std::abs(end.z() - usual - slabs[s].elevation);
      if (offset <= best_offset) {
        best = s;
        best_offset = offset;
      }
    }
    if (best < slabs.size()) {
      ++votes[best];
      ++stats.flight_ends_on_floor;
    }
  }
  return votes;
}

}  // namespace

StoreySegmentation segmentStoreys(MapCloud& map,
                                  const std::vector<Eigen::Vector3d>& keyframe_positions,
                                  const StoreysConfig& config, const ProgressFn& progress) {
  config.validate();
  StoreySegmentation result;
  StoreySegmentationStats& stats = result.stats;
  std::fill(map.storey.begin(), map.storey.end(), kNoStorey);
  std::fill(map.flags.begin(), map.flags.end(), std::uint8_t{0});
  auto report = [&](double fraction, const char* stage) {
    if (progress && !progress(fraction, stage)) throw Cancelled();
  };

  // 1. Subsample, normals oriented towards the observing sensor.
  auto t0 = std::chrono::steady_clock::now();
  report(0.0, "storeys: normals");
  const Subsample sub = subsample(map, config.voxel_size);
  stats.subsampled_points = sub.points.size();
  if (sub.points.size() < 16) return result;
  // The neighbours of the normals (the point and its normal_neighbours nearest)
  // and of the region growing (normal_neighbours, the point among them).
  const std::size_t k_nearest = std::min<std::size_t>(
      static_cast<std::size_t>(config.normal_neighbours), sub.points.size() - 1);
  const NearestNeighbours neighbours = findNearestNeighbours(sub.points, k_nearest + 1);
  std::vector<Eigen::Vector3d> normals = estimateNormals(sub.points, neighbours);
  auto sensorOf = [&](std::int32_t keyframe) -> const Eigen::Vector3d* {
    if (keyframe < 0 || static_cast<std::size_t>(keyframe) >= keyframe_positions.size())
      return nullptr;
    const Eigen::Vector3d& s = keyframe_positions[static_cast<std::size_t>(keyframe)];
    return s.allFinite() ? &s : nullptr;
  };
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const Eigen::Vector3d* s = sensorOf(sub.keyframe[i]);
    const bool flip = s ? normals[i].dot(*s - sub.points[i]) < 0.0 : normals[i].z() < 0.0;
    if (flip) normals[i] = -normals[i];
  }
  stats.seconds_normals = secondsSince(t0);

  // 2. Planar regions; horizontal ones facing up (floor) or down (ceiling).
  t0 = std::chrono::steady_clock::now();
  report(0.3, "storeys: planes");
  const double cell_area = config.voxel_size * config.voxel_size;
  const std::size_t min_points =
      std::max<std::size_t>(3, static_cast<std::size_t>(0.5 * config.min_region_area / cell_area));
  const std::vector<PlanarRegion> regions =
      detectPlanarRegions(sub.points, normals, neighbours, k_nearest, config.plane_distance,
                          config.plane_angle_deg, min_points);
  stats.regions = regions.size();
  // A region's side is the majority of its points' sensor-oriented normals
  // (a single point seen at a grazing angle may be oriented wrongly); its
  // points take the region's oriented normal.
  for (const PlanarRegion& region : regions) {
    double votes = 0.0;
    for (std::size_t i : region.indices) votes += normals[i].dot(region.normal) >= 0.0 ? 1.0 : -1.0;
    const Eigen::Vector3d oriented = votes >= 0.0 ? region.normal : Eigen::Vector3d(-region.normal);
    for (std::size_t i : region.indices) normals[i] = oriented;
  }
  const double cos_horizontal = std::cos(config.horizontal_angle_deg * kDegToRad);
  std::vector<HorizontalRegion> up, down;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const PlanarRegion& region = regions[r];
    if (std::abs(region.normal.z()) < cos_horizontal) continue;
    const double area = cellArea(region.indices, sub.points, config.voxel_size);
    if (area < config.min_region_area) continue;
    std::vector<double> z;
    z.reserve(region.indices.size());
    for (std::size_t i : region.indices) z.push_back(sub.points[i].z());
    HorizontalRegion h{r, median(std::move(z)), area};
    (normals[region.indices.front()].z() > 0.0 ? up : down).push_back(h);
  }
  stats.floor_candidates = up.size();
  stats.ceiling_candidates = down.size();
  stats.seconds_regions = secondsSince(t0);

  // 3. Floor slabs -> storeys.
  t0 = std::chrono::steady_clock::now();
  report(0.6, "storeys: slabs");
  const std::vector<Slab> floor_slabs =
      clusterByElevation(up, regions, sub.points, config.slab_tolerance, config.voxel_size);
  const std::vector<Slab> ceiling_slabs =
      clusterByElevation(down, regions, sub.points, config.slab_tolerance, config.voxel_size);
  stats.floor_slabs = floor_slabs.size();
  std::vector<std::size_t> by_area;
  for (std::size_t s = 0; s < floor_slabs.size(); ++s) {
    if (floor_slabs[s].area >= config.min_floor_area)
      by_area.push_back(s);
    else
      ++stats.slabs_too_small;
  }
  // Slabs the stairs arrive at come first, then by area: of a split level's
  // two floors (a wing a few steps or a ramp higher, possibly the larger), the
  // storey's floor is the one its stair flights start and end on.
  const std::vector<std::size_t> votes =
      flightEndVotes(floor_slabs, up, regions, sub.points, keyframe_positions, stats);
  std::sort(by_area.begin(), by_area.end(), [&](std::size_t a, std::size_t b) {
    const bool stairs_a = votes[a] > 0, stairs_b = votes[b] > 0;
    if (stairs_a != stairs_b) return stairs_a;
    return floor_slabs[a].area > floor_slabs[b].area;
  });
  std::vector<std::size_t> floors;
  for (std::size_t s : by_area) {
    bool clear = true;
    for (std::size_t f : floors)
      clear = clear && std::abs(floor_slabs[s].elevation - floor_slabs[f].elevation) >=
                           config.min_storey_height;
    if (clear)
      floors.push_back(s);
    else
      ++stats.slabs_too_close;
  }
  std::sort(floors.begin(), floors.end(), [&](std::size_t a, std::size_t b) {
    return floor_slabs[a].elevation < floor_slabs[b].elevation;
  });
  if (floors.empty()) return result;
  const std::size_t n = floors.size();
  std::vector<double> floor_z(n);
  for (std::size_t k = 0; k < n; ++k) floor_z[k] = floor_slabs[floors[k]].elevation;
  auto upperOf = [&](std::size_t k) {
    return k + 1 < n ? floor_z[k + 1] : floor_z[k] + config.max_clear_height;
  };
  for (std::size_t k = 0; k < n; ++k) {
    StoreyInfo info;
    info.index = static_cast<int>(k);
    info.floor_elevation = floor_z[k];
    info.floor_area_detected = floor_slabs[floors[k]].area;
    if (k + 1 < n) info.height = floor_z[k + 1] - floor_z[k];
    const double lo = floor_z[k] + config.min_clear_height;
    const double hi = std::min(upperOf(k), floor_z[k] + config.max_clear_height);
    const Slab* best = nullptr;
    for (const Slab& c : ceiling_slabs) {
      if (c.elevation < lo || c.elevation > hi) continue;
      if (!best || c.area > best->area) best = &c;
    }
    if (best) {
      info.ceiling_elevation = best->elevation;
      info.clear_height = best->elevation - floor_z[k];
    }
    result.storeys.push_back(info);
  }

  // 4. Stairs: 2D cells holding upward surfaces between two floors (steps,
  // landings), near the keyframes where the sensor is above its usual height.
  const double margin = 0.5 * config.floor_tolerance;
  auto storeyOf = [&](double z) -> std::size_t {
    std::size_t k = 0;
    while (k + 1 < n && z >= floor_z[k + 1] - config.floor_tolerance) ++k;
    return k;
  };
  std::vector<std::vector<Eigen::Vector2d>> stair_keyframes(n);
  bool have_trajectory = false;
  {
    std::vector<double> heights;
    std::vector<std::pair<std::size_t, Eigen::Vector3d>> placed;
    for (const Eigen::Vector3d& s : keyframe_positions) {
      if (!s.allFinite() || s.z() < floor_z[0]) continue;
      const std::size_t k = storeyOf(s.z());
      heights.push_back(s.z() - floor_z[k]);
      placed.emplace_back(k, s);
    }
    if (!placed.empty()) {
      have_trajectory = true;
      const double usual = median(heights);
      for (const auto& [k, s] : placed) {
        if (s.z() - floor_z[k] - usual > config.stairs_min_rise)
          stair_keyframes[k].push_back(s.head<2>());
      }
    }
  }
  std::vector<bool> in_floor(sub.points.size(), false);
  for (std::size_t f : floors)
    forEachSlabPoint(floor_slabs[f], up, regions, [&](std::size_t i) { in_floor[i] = true; });
  const double inv_cell = 1.0 / config.stairs_cell_size;
  std::vector<std::unordered_map<std::uint64_t, int>> step_points(n);
  const double gate2 = config.stairs_trajectory_distance * config.stairs_trajectory_distance;
  for (std::size_t i = 0; i < sub.points.size(); ++i) {
    if (in_floor[i] || normals[i].z() < cos_horizontal) continue;
    const Eigen::Vector3d& p = sub.points[i];
    if (p.z() < floor_z[0]) continue;
    const std::size_t k = storeyOf(p.z());
    if (p.z() <= floor_z[k] + margin || p.z() >= upperOf(k) - margin) continue;
    if (have_trajectory) {
      bool near = false;
      for (const Eigen::Vector2d& s : stair_keyframes[k])
        if ((s - p.head<2>()).squaredNorm() <= gate2) {
          near = true;
          break;
        }
      if (!near) continue;
    }
    ++step_points[k][cellKey(p.x(), p.y(), inv_cell)];
  }
  std::vector<std::unordered_set<std::uint64_t>> stair_cells(n);
  for (std::size_t k = 0; k < n; ++k) {
    for (const auto& [key, count] : step_points[k]) {
      if (count < 3) continue;
      const std::int64_t bias = std::int64_t{1} << 20;
      const std::uint64_t mask = (std::uint64_t{1} << 21) - 1;
      const std::int64_t ci = static_cast<std::int64_t>((key >> 42) & mask) - bias;
      const std::int64_t cj = static_cast<std::int64_t>((key >> 21) & mask) - bias;
      for (std::int64_t di = -1; di <= 1; ++di)
        for (std::int64_t dj = -1; dj <= 1; ++dj)
          stair_cells[k].insert(packVoxel(ci + di, cj + dj, 0));
    }
    stats.stair_cells += stair_cells[k].size();
  }

  // 5. Labels of every map point.
  std::vector<std::unordered_set<std::uint64_t>> floor_cells(n);
  const double inv_voxel = 1.0 / config.voxel_size;
  for (std::size_t k = 0; k < n; ++k)
    forEachSlabPoint(floor_slabs[floors[k]], up, regions, [&](std::size_t i) {
      floor_cells[k].insert(cellKey(sub.points[i].x(), sub.points[i].y(), inv_voxel));
    });
  for (std::size_t i = 0; i < map.size(); ++i) {
    const Eigen::Vector3f& p = map.positions[i];
    if (!p.allFinite()) continue;
    const double z = p.z();
    const std::size_t k = storeyOf(z);
    map.storey[i] = static_cast<std::int16_t>(k);
    StoreyInfo& info = result.storeys[k];
    ++info.points;
    if (std::abs(z - floor_z[k]) <= config.plane_distance &&
        floor_cells[k].count(cellKey(p.x(), p.y(), inv_voxel)))
      map.flags[i] |= kMapPointFloor;
    if (z > floor_z[k] + margin && z < upperOf(k) - config.floor_tolerance &&
        stair_cells[k].count(cellKey(p.x(), p.y(), inv_cell))) {
      map.flags[i] |= kMapPointStairs;
      ++info.stair_points;
    }
  }
  stats.seconds_labels = secondsSince(t0);

  // 6. Footprints.
  t0 = std::chrono::steady_clock::now();
  report(0.8, "storeys: footprints");
  // One storey's alpha shape per thread (each independent of the others).
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t k) {
    std::vector<Eigen::Vector2d> xy;
    forEachSlabPoint(floor_slabs[floors[k]], up, regions,
                     [&](std::size_t i) { xy.push_back(sub.points[i].head<2>()); });
    const Footprint footprint = alphaShapeFootprint(xy, config.footprint_alpha);
    result.storeys[k].footprint = footprint.polygon;
    result.storeys[k].footprint_area = footprint.area;
  });
  stats.seconds_footprints = secondsSince(t0);
  report(1.0, "storeys");
  return result;
}

}  // namespace storey
