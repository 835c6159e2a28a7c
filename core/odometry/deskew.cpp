#include "odometry/deskew.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace storey {

namespace {

/// The transform of a point time into the reference frame.
struct Transform {
  Eigen::Matrix3d R_ref_lidar;
  Eigen::Vector3d t_ref_lidar;
};

/// The transforms computed so far, by the exact bits of the point time they
/// were computed for: sensors that order a scan by beam (an Ouster's cloud is
/// row after row) come back to a column's time once per beam, and the same
/// time gives the same transform. Open addressing; full at half its capacity,
/// after which further times are computed without being kept.
class TransformsByTime {
 public:
  explicit TransformsByTime(std::size_t points) {
    std::size_t capacity = 1024;
    while (capacity < points / 8) capacity *= 2;
    slots_.assign(capacity, kEmpty);
    mask_ = capacity - 1;
    keys_.reserve(capacity / 2);
    transforms_.reserve(capacity / 2);
  }

  /// The transform kept for `time`, or nullptr.
  const Transform* find(float time) const {
    const std::uint32_t key = bitsOf(time);
    for (std::size_t i = slotOf(key);; i = (i + 1) & mask_) {
      const std::uint32_t index = slots_[i];
      if (index == kEmpty) return nullptr;
      if (keys_[index] == key) return &transforms_[index];
    }
  }

  void keep(float time, const Transform& transform) {
    if (transforms_.size() >= (mask_ + 1) / 2) return;
    const std::uint32_t key = bitsOf(time);
    std::size_t i = slotOf(key);
    while (slots_[i] != kEmpty) i = (i + 1) & mask_;
    slots_[i] = static_cast<std::uint32_t>(transforms_.size());
    keys_.push_back(key);
    transforms_.push_back(transform);
  }

 private:
  static constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  static std::uint32_t bitsOf(float time) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &time, sizeof(bits));
    return bits;
  }
  std::size_t slotOf(std::uint32_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B1u) >> 7) & mask_;
  }

  std::vector<std::uint32_t> slots_;  ///< index into keys_ and transforms_, or kEmpty
  std::vector<std::uint32_t> keys_;
  std::vector<Transform> transforms_;
  std::size_t mask_ = 0;
};

}  // namespace

Scan deskewScan(const Scan& scan, const ImuPoseTable& table, const SensorConfig& sensor) {
  Scan out;
  out.stamp_ns = scan.stamp_ns;
  out.frame_id = scan.frame_id;
  out.points.resize(scan.points.size());
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
  // Consecutive points fire microseconds apart (a VLP-16 fires its 16 lasers
  // within 55 us): the transform is reused while a point's time is within
  // kTimeTolerance of the one it was computed for (at 1 m/s and 1 rad/s the
  // error is below 0.03 mm and 3e-5 rad). Otherwise the transform of that
  // exact time is reused when it was computed before.
  constexpr float kTimeTolerance = 30e-6f;
  TransformsByTime computed(scan.points.size());
  float cached_time = std::numeric_limits<float>::quiet_NaN();
  Transform current{Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()};
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const ScanPoint& in = scan.points[i];
    if (!(std::abs(in.time - cached_time) <= kTimeTolerance)) {
      if (const Transform* kept = computed.find(in.time)) {
        current = *kept;
      } else {
        current = transformAt(in.time);
        computed.keep(in.time, current);
      }
      cached_time = in.time;
    }
    ScanPoint& o = out.points[i];
    o = in;
    o.p = (current.R_ref_lidar * in.p.cast<double>() + current.t_ref_lidar).cast<float>();
  }
  return out;
}

}  // namespace storey
