#include "odometry/deskew.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "common/parallel_chunks.h"

namespace storey {

namespace {

/// The transform of a point time into the reference frame.
struct Transform {
  Eigen::Matrix3d R_ref_lidar;
  Eigen::Vector3d t_ref_lidar;
};

/// The distinct point times a scan's transforms are computed for, by their
/// exact bits: sensors that order a scan by beam (an Ouster's cloud is row
/// after row) come back to a column's time once per beam, and the same time
/// gives the same transform. Open addressing, grown at half full.
class TimesByBits {
 public:
  explicit TimesByBits(std::size_t expected) {
    std::size_t capacity = 1024;
    while (capacity < 2 * expected) capacity *= 2;
    slots_.assign(capacity, kEmpty);
  }

  /// The index of `time` among the distinct times, added when new.
  std::uint32_t indexOf(float time) {
    const std::uint32_t key = bitsOf(time);
    std::size_t i = slotOf(key);
    for (;; i = (i + 1) & (slots_.size() - 1)) {
      const std::uint32_t index = slots_[i];
      if (index == kEmpty) break;
      if (keys_[index] == key) return index;
    }
    const auto index = static_cast<std::uint32_t>(keys_.size());
    slots_[i] = index;
    keys_.push_back(key);
    times_.push_back(time);
    if (2 * keys_.size() > slots_.size()) grow();
    return index;
  }

  const std::vector<float>& times() const { return times_; }

 private:
  static constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  static std::uint32_t bitsOf(float time) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &time, sizeof(bits));
    return bits;
  }
  std::size_t slotOf(std::uint32_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B1u) >> 7) & (slots_.size() - 1);
  }
  void grow() {
    slots_.assign(slots_.size() * 2, kEmpty);
    for (std::size_t index = 0; index < keys_.size(); ++index) {
      std::size_t i = slotOf(keys_[index]);
      while (slots_[i] != kEmpty) i = (i + 1) & (slots_.size() - 1);
      slots_[i] = static_cast<std::uint32_t>(index);
    }
  }

  std::vector<std::uint32_t> slots_;  ///< index into keys_ and times_, or kEmpty
  std::vector<std::uint32_t> keys_;
  std::vector<float> times_;
};

}  // namespace

Scan deskewScan(const Scan& scan, const ImuPoseTable& table, const SensorConfig& sensor,
                const ParallelChunks* parallel) {
  Scan out;
  out.stamp_ns = scan.stamp_ns;
  out.frame_id = scan.frame_id;
  const std::size_t n = scan.points.size();
  out.points.resize(n);
  const double t_ref = table.secondsSinceStart(scan.stamp_ns, sensor.time_offset_lidar_to_imu);
  const Pose T_imu_lidar = sensor.T_imu_lidar;
  const Pose T_lidar_imu = T_imu_lidar.inverse();
  const Pose T_ref_world = (table.T_world_imu(t_ref)).inverse();
  const Eigen::Matrix3d R_il = T_imu_lidar.rotationMatrix();
  const Eigen::Vector3d t_il = T_imu_lidar.translation();
  const auto transformAt = [&](float time) {
    Eigen::Quaterniond q_world_imu;
    Eigen::Vector3d p_world_imu;
    table.interpolate(t_ref + time, q_world_imu, p_world_imu);
    // T_lidar(ref)_lidar(t) = T_lidar_imu * T_ref_world * T_world_imu(t) * T_imu_lidar
    const Pose T_ref_imu_t = T_ref_world * Pose(q_world_imu, p_world_imu);
    const Pose T = T_lidar_imu * T_ref_imu_t;
    return Transform{T.rotationMatrix() * R_il, T.rotationMatrix() * t_il + T.translation()};
  };
  // 1. The time each point's transform is computed at (from the times alone,
  // in the points' order). Consecutive points fire microseconds apart (a
  // VLP-16 fires its 16 lasers within 55 us): a point within kTimeTolerance
  // of the time the previous point's transform was computed at shares it (at
  // 1 m/s and 1 rad/s the error is below 0.03 mm and 3e-5 rad); otherwise its
  // own time is taken, whose transform may have been computed before.
  constexpr float kTimeTolerance = 30e-6f;
  std::vector<std::uint32_t> time_of_point(n);
  TimesByBits times(n / 16 + 16);
  float cached_time = std::numeric_limits<float>::quiet_NaN();
  std::uint32_t cached = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float time = scan.points[i].time;
    if (!(std::abs(time - cached_time) <= kTimeTolerance)) {
      cached = times.indexOf(time);
      cached_time = time;
    }
    time_of_point[i] = cached;
  }
  // 2. The transforms, then 3. the points, in chunks of a fixed size on the
  // caller's threads: the same bytes whatever their number.
  const std::vector<float>& distinct = times.times();
  std::vector<Transform> transforms(distinct.size());
  const auto run = [parallel](std::size_t count, std::size_t chunk, const auto& fn) {
    const std::size_t chunks = (count + chunk - 1) / chunk;
    const auto range = [&](std::size_t c) {
      for (std::size_t i = c * chunk; i < std::min(count, (c + 1) * chunk); ++i) fn(i);
    };
    if (parallel != nullptr && chunks > 1)
      parallel->run(chunks, range);
    else
      for (std::size_t c = 0; c < chunks; ++c) range(c);
  };
  run(distinct.size(), 256, [&](std::size_t k) { transforms[k] = transformAt(distinct[k]); });
  run(n, 4096, [&](std::size_t i) {
    const ScanPoint& in = scan.points[i];
    const Transform& current = transforms[time_of_point[i]];
    ScanPoint& o = out.points[i];
    o = in;
    o.p = (current.R_ref_lidar * in.p.cast<double>() + current.t_ref_lidar).cast<float>();
  });
  return out;
}

}  // namespace storey
