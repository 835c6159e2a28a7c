#include "map/map_builder.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include "common/error.h"
#include "common/parallel_chunks.h"
#include "map/chunked_array.h"
#include "types/voxel_hash.h"

namespace storey {

namespace {

/// A stored point placed in the world: its voxel's key, its position from
/// the voxel's corner, and where it came from (scan and point, which order
/// the voxels).
struct PlacedPoint {
  std::uint64_t key;
  Eigen::Vector3f local;
  float intensity;
  float dt;
  std::uint32_t entry;  ///< scan, in the order added
  std::uint32_t point;  ///< in its scan's stored points
  std::uint8_t partition;
};

/// The voxels of one partition of the key space: sums relative to the
/// voxel's corner (small numbers, exact enough in float) and the first
/// return (its scan and point, which keyframe and stamp; its time offset).
/// 32 bytes a voxel, in chunks (no reallocation spikes).
class Partition {
 public:
  Partition() = default;
  Partition(const Partition&) = delete;  // the index refers to keys_
  Partition& operator=(const Partition&) = delete;

  struct Acc {
    float sx, sy, sz, si;
    std::uint32_t n;
    std::uint32_t entry;  ///< of the first return
    std::uint32_t point;  ///< of the first return in its scan
    float dt;             ///< time offset of the first return in its scan [s]
  };

  /// Adds the block's points of partition `self`, in the block's order.
  /// Points go through in batches: their voxels' slots are prefetched first,
  /// then the keys those slots point to, then looked up in order, then the
  /// found voxels' sums (prefetched by the lookup) are added to in order. Each
  /// voxel sees the same additions in the same order as one point at a time.
  void merge(const std::vector<PlacedPoint>& block, std::size_t self) {
    constexpr std::size_t kBatch = 64;
    const PlacedPoint* batch[kBatch];
    std::uint32_t voxel[kBatch];
    bool inserted[kBatch];
    std::size_t i = 0;
    while (i < block.size()) {
      std::size_t count = 0;
      for (; i < block.size() && count < kBatch; ++i) {
        if (block[i].partition != self) continue;
        batch[count++] = &block[i];
        index_.prefetch(block[i].key);
      }
      for (std::size_t b = 0; b < count; ++b) index_.prefetchKey(batch[b]->key);
      for (std::size_t b = 0; b < count; ++b) {
        const PlacedPoint& q = *batch[b];
        voxel[b] = index_.findOrInsert(q.key, inserted[b]);
        if (inserted[b]) {
          acc_.push_back(
              {q.local.x(), q.local.y(), q.local.z(), q.intensity, 1, q.entry, q.point, q.dt});
        } else {
          __builtin_prefetch(&acc_[voxel[b]], 1);
        }
      }
      for (std::size_t b = 0; b < count; ++b) {
        if (inserted[b]) continue;
        const PlacedPoint& q = *batch[b];
        Acc& a = acc_[voxel[b]];
        a.sx += q.local.x();
        a.sy += q.local.y();
        a.sz += q.local.z();
        a.si += q.intensity;
        ++a.n;
      }
    }
  }

  /// The table is not needed once every point is in: freed first.
  void releaseIndex() { index_.release(); }
  std::size_t size() const { return acc_.size(); }
  const Acc& acc(std::size_t v) const { return acc_[v]; }
  std::uint64_t key(std::size_t v) const { return keys_[v]; }
  /// Frees the voxels before `v` (emitted).
  void releaseBefore(std::size_t v) {
    acc_.releaseBefore(v);
    keys_.releaseBefore(v);
  }

 private:
  ChunkedArray<Acc> acc_;
  ChunkedArray<std::uint64_t> keys_;  // keys_[v]: voxel v's key, appended by the index
  // Grown with the map (not sized by the points stored, which grow with the log);
  // 4 bytes a slot over `keys_`.
  VoxelIndexOverKeys<ChunkedArray<std::uint64_t>> index_{keys_, std::size_t{1} << 19};
};

}  // namespace

void MapCloud::reserve(std::size_t n) {
  positions.reserve(n);
  intensity.reserve(n);
  time.reserve(n);
  keyframe.reserve(n);
  storey.reserve(n);
  flags.reserve(n);
}

void MapCloud::clear() {
  *this = MapCloud();
}

void MapCloud::pushFrom(const MapCloud& other, std::size_t i) {
  positions.push_back(other.positions[i]);
  intensity.push_back(other.intensity[i]);
  time.push_back(other.time[i]);
  keyframe.push_back(other.keyframe[i]);
  storey.push_back(other.storey[i]);
  flags.push_back(other.flags[i]);
}

void MapCloud::bounds(Eigen::Vector3d& min, Eigen::Vector3d& max) const {
  if (positions.empty()) {
    min.setZero();
    max.setZero();
    return;
  }
  Eigen::Vector3f lo = positions.front(), hi = positions.front();
  for (const Eigen::Vector3f& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  min = lo.cast<double>();
  max = hi.cast<double>();
}

MapBuilder::MapBuilder(const MapConfig& config) : config_(config) {
  if (!(config_.voxel_size > 0.0)) throw Error("map.voxel_size must be positive");
  if (!(config_.max_range > 0.0)) throw Error("map.max_range must be positive");
  if (config_.spill_to_disk) {
    // Anonymous: removed by the system when closed, also after a crash.
    file_ = std::tmpfile();
    if (!file_)
      throw Error(std::string("map: cannot create a temporary file for the map scans (") +
                  std::strerror(errno) + "); set map.spill_to_disk: false to keep them in RAM");
  }
}

MapBuilder::~MapBuilder() {
  if (file_) std::fclose(file_);
}

void MapBuilder::addScan(int map_scan, const Scan& scan, int keyframe) {
  if (map_scan < 0) throw Error("map: scan index must be >= 0, got " + std::to_string(map_scan));
  if (static_cast<std::size_t>(map_scan) >= entry_of_scan_.size())
    entry_of_scan_.resize(static_cast<std::size_t>(map_scan) + 1, -1);
  if (entry_of_scan_[static_cast<std::size_t>(map_scan)] >= 0)
    throw Error("map: scan " + std::to_string(map_scan) + " was added twice");

  // Downsample in the LiDAR frame: centroid of each voxel, mean intensity,
  // time of the voxel's first point (the same rule as the map's merge).
  const double inv = 1.0 / config_.voxel_size;
  const float max_range2 = static_cast<float>(config_.max_range * config_.max_range);
  VoxelIndex index(scan.points.size() / 2 + 16);
  struct Acc {
    double x, y, z;
    float intensity, dt;
    std::uint32_t n;
  };
  std::vector<Acc> acc;
  acc.reserve(scan.points.size() / 2 + 16);
  for (const ScanPoint& sp : scan.points) {
    ++stats_.points_in;
    if (!sp.p.allFinite()) {
      ++stats_.points_non_finite;
      continue;
    }
    if (sp.p.squaredNorm() > max_range2) {
      ++stats_.points_beyond_range;
      continue;
    }
    const Eigen::Vector3d p = sp.p.cast<double>();
    bool inserted = false;
    const std::uint32_t v = index.findOrInsert(voxelKey(p, inv), inserted);
    if (inserted) {
      acc.push_back({p.x(), p.y(), p.z(), sp.intensity, sp.time, 1});
    } else {
      Acc& a = acc[v];
      a.x += p.x();
      a.y += p.y();
      a.z += p.z();
      a.intensity += sp.intensity;
      a.dt = std::min(a.dt, sp.time);
      ++a.n;
    }
  }
  std::vector<StoredPoint> points;
  points.reserve(acc.size());
  for (const Acc& a : acc) {
    const double n = a.n;
    points.push_back({static_cast<float>(a.x / n), static_cast<float>(a.y / n),
                      static_cast<float>(a.z / n), static_cast<float>(a.intensity / n), a.dt});
  }

  Entry entry;
  entry.map_scan = map_scan;
  entry.keyframe = keyframe >= 0 ? keyframe : map_scan;
  entry.stamp_ns = scan.stamp_ns;
  entry.offset = stored_points_;
  entry.count = points.size();
  if (file_) {
    if (!points.empty() &&
        std::fwrite(points.data(), sizeof(StoredPoint), points.size(), file_) != points.size())
      throw Error("map: cannot write the map scans' temporary file (disk full?)");
  } else {
    memory_.insert(memory_.end(), points.begin(), points.end());
  }
  stored_points_ += points.size();
  entry_of_scan_[static_cast<std::size_t>(map_scan)] = static_cast<int>(entries_.size());
  entries_.push_back(entry);
  ++stats_.scans;
  stats_.points_stored = static_cast<std::int64_t>(stored_points_);
  stats_.stored_bytes = static_cast<std::int64_t>(stored_points_ * sizeof(StoredPoint));
}

void MapBuilder::readPoints(const Entry& entry, std::vector<StoredPoint>& out) const {
  out.resize(entry.count);
  if (entry.count == 0) return;
  if (!file_) {
    std::copy(memory_.begin() + static_cast<std::ptrdiff_t>(entry.offset),
              memory_.begin() + static_cast<std::ptrdiff_t>(entry.offset + entry.count),
              out.begin());
    return;
  }
  if (std::fflush(file_) != 0 ||
      std::fseek(file_, static_cast<long>(entry.offset * sizeof(StoredPoint)), SEEK_SET) != 0 ||
      std::fread(out.data(), sizeof(StoredPoint), entry.count, file_) != entry.count)
    throw Error("map: cannot read back the map scans' temporary file");
  // Appends continue at the end.
  std::fseek(file_, 0, SEEK_END);
}

MapCloud MapBuilder::build(const std::vector<Pose>& T_world_lidar_per_scan,
                           const ProgressFn& progress) const {
  for (const Entry& e : entries_) {
    if (static_cast<std::size_t>(e.map_scan) >= T_world_lidar_per_scan.size())
      throw Error("map: scan " + std::to_string(e.map_scan) + " has no pose (" +
                  std::to_string(T_world_lidar_per_scan.size()) + " poses given)");
  }
  const double inv = 1.0 / config_.voxel_size;
  const std::size_t parts = static_cast<std::size_t>(std::max(config_.build_threads, 1));
  std::vector<Partition> partitions(parts);
  const ParallelChunks parallel(static_cast<int>(parts));

  // The scans go through in blocks: read (one file, one thread), placed and
  // keyed in chunks of points on every thread, then merged into the
  // partitions, one thread each. A voxel belongs to one partition (by the top
  // bits of its key's hash; the table's slot takes the low bits) and sees the
  // same points in the same order whatever the number of partitions, so its
  // sums are the same; the voxels are emitted in the order of their first
  // return, as one partition would have them: the same cloud.
  constexpr std::size_t kBlockPoints = std::size_t{1} << 18;
  constexpr std::size_t kChunkPoints = std::size_t{1} << 14;
  struct Span {
    std::size_t entry, begin, count;
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
  };
  std::vector<Span> spans;
  std::vector<StoredPoint> points, scan_points;
  std::vector<PlacedPoint> block;
  std::size_t e = 0;
  while (e < entries_.size()) {
    spans.clear();
    points.clear();
    while (e < entries_.size() && points.size() < kBlockPoints) {
      readPoints(entries_[e], scan_points);
      const Pose& T = T_world_lidar_per_scan[static_cast<std::size_t>(entries_[e].map_scan)];
      spans.push_back({e, points.size(), scan_points.size(), T.rotationMatrix(), T.translation()});
      points.insert(points.end(), scan_points.begin(), scan_points.end());
      ++e;
    }
    block.resize(points.size());
    const std::size_t chunks = (points.size() + kChunkPoints - 1) / kChunkPoints;
    parallel.run(chunks, [&](std::size_t c) {
      const std::size_t begin = c * kChunkPoints;
      const std::size_t end = std::min(points.size(), begin + kChunkPoints);
      std::size_t s = 0;
      for (std::size_t i = begin; i < end; ++i) {
        while (i >= spans[s].begin + spans[s].count) ++s;
        const Span& span = spans[s];
        const StoredPoint& sp = points[i];
        const Eigen::Vector3d p = span.R * Eigen::Vector3d(sp.x, sp.y, sp.z) + span.t;
        const Eigen::Vector3d cell(std::floor(p.x() * inv), std::floor(p.y() * inv),
                                   std::floor(p.z() * inv));
        PlacedPoint& q = block[i];
        q.key = packVoxel(static_cast<std::int64_t>(cell.x()), static_cast<std::int64_t>(cell.y()),
                          static_cast<std::int64_t>(cell.z()));
        q.local = (p - cell * config_.voxel_size).cast<float>();
        q.intensity = sp.intensity;
        q.dt = sp.dt;
        q.entry = static_cast<std::uint32_t>(span.entry);
        q.point = static_cast<std::uint32_t>(i - span.begin);
        q.partition = static_cast<std::uint8_t>((voxelHash(q.key) >> 56) % parts);
      }
    });
    parallel.run(parts, [&](std::size_t p) { partitions[p].merge(block, p); });
    if (progress && !progress(static_cast<double>(e) / static_cast<double>(entries_.size()), "map"))
      throw Cancelled();
  }
  std::vector<PlacedPoint>().swap(block);
  std::vector<StoredPoint>().swap(points);

  std::size_t voxels = 0;
  for (Partition& p : partitions) {
    p.releaseIndex();  // the hash tables are not needed any more: freed first
    voxels += p.size();
  }
  MapCloud cloud;
  cloud.reserve(voxels);
  constexpr std::int64_t kBias = std::int64_t{1} << 20;
  constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
  std::vector<std::size_t> next(parts, 0);
  for (std::size_t emitted = 0; emitted < voxels; ++emitted) {
    // The partition whose next voxel has the earliest first return.
    std::size_t from = parts;
    for (std::size_t p = 0; p < parts; ++p) {
      if (next[p] == partitions[p].size()) continue;
      if (from == parts) {
        from = p;
        continue;
      }
      const Partition::Acc& a = partitions[p].acc(next[p]);
      const Partition::Acc& b = partitions[from].acc(next[from]);
      if (a.entry < b.entry || (a.entry == b.entry && a.point < b.point)) from = p;
    }
    Partition& partition = partitions[from];
    const std::size_t v = next[from]++;
    const Partition::Acc& a = partition.acc(v);
    const std::uint64_t key = partition.key(v);
    const Entry& first = entries_[a.entry];
    const Eigen::Vector3d corner(
        static_cast<double>(static_cast<std::int64_t>((key >> 42) & kMask) - kBias),
        static_cast<double>(static_cast<std::int64_t>((key >> 21) & kMask) - kBias),
        static_cast<double>(static_cast<std::int64_t>(key & kMask) - kBias));
    const float n = static_cast<float>(a.n);
    const Eigen::Vector3d p =
        corner * config_.voxel_size + Eigen::Vector3d(a.sx / n, a.sy / n, a.sz / n);
    cloud.positions.push_back(p.cast<float>());
    cloud.intensity.push_back(a.si / n);
    cloud.time.push_back(nsToSeconds(first.stamp_ns) + static_cast<double>(a.dt));
    cloud.keyframe.push_back(first.keyframe);
    cloud.storey.push_back(kNoStorey);
    cloud.flags.push_back(0);
    // The accumulators read so far are freed as the cloud fills (its pages are touched as written).
    partition.releaseBefore(v);
  }
  return cloud;
}

}  // namespace storey
