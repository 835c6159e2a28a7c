#include "sim/lidar_simulator.h"

#include <algorithm>
#include <cmath>

#include "sim/random.h"

namespace storey::sim {

LidarSimulator::LidarSimulator(const TriangleMesh& mesh, const Trajectory& trajectory,
                               const SensorsSpec& sensors, const LidarNoise& noise,
                               std::uint64_t seed)
    : trajectory_(trajectory),
      T_body_lidar_(sensors.T_body_lidar),
      spec_(sensors.lidar),
      noise_(noise),
      seed_(seed),
      revolution_ns_(static_cast<std::int64_t>(std::llround(1e9 / sensors.lidar.rotation_rate))),
      frame_id_(sensors.lidar_frame_id),
      caster_(mesh) {
  for (const Triangle& t : mesh.triangles()) reflectivity_.push_back(t.reflectivity);
}

int LidarSimulator::scanCount(double duration) const {
  const std::int64_t span = static_cast<std::int64_t>(std::floor(duration * 1e9));
  // Scan n is complete when its last firing is inside the span.
  int n = static_cast<int>(span / revolution_ns_);
  while (n > 0 && scanEndNs(n - 1) > span) --n;
  return n;
}

std::int64_t LidarSimulator::firstSequence(int n) const {
  const std::int64_t start = n * revolution_ns_;
  return (start + vlp16::kSequencePeriodNs - 1) / vlp16::kSequencePeriodNs;
}

std::int64_t LidarSimulator::scanStampNs(int n) const {
  return firstSequence(n) * vlp16::kSequencePeriodNs;
}

std::int64_t LidarSimulator::scanEndNs(int n) const {
  return (firstSequence(n + 1) - 1) * vlp16::kSequencePeriodNs +
         (vlp16::kLasers - 1) * vlp16::kFiringIntervalNs;
}

Scan LidarSimulator::simulateScan(int n, std::vector<vlp16::FiringSequence>* firings) const {
  Random rng(seed_, 0x11da2000ULL + static_cast<std::uint64_t>(n));
  Scan scan;
  scan.frame_id = frame_id_;
  scan.stamp_ns = scanStampNs(n);
  const std::int64_t k0 = firstSequence(n), k1 = firstSequence(n + 1);
  scan.points.reserve(static_cast<std::size_t>((k1 - k0) * vlp16::kLasers));
  if (firings != nullptr) {
    firings->clear();
    firings->reserve(static_cast<std::size_t>(k1 - k0));
  }

  // Per laser: elevation sines/cosines and the azimuth advance since the
  // sequence's first firing (cos/sin of id * 2.304 us of rotation).
  double cos_elevation[vlp16::kLasers], sin_elevation[vlp16::kLasers];
  double cos_advance[vlp16::kLasers], sin_advance[vlp16::kLasers];
  for (int id = 0; id < vlp16::kLasers; ++id) {
    cos_elevation[id] = std::cos(vlp16::elevation(id));
    sin_elevation[id] = std::sin(vlp16::elevation(id));
    const double advance = 2.0 * M_PI * (id * vlp16::kFiringIntervalNs) / revolution_ns_;
    cos_advance[id] = std::cos(advance);
    sin_advance[id] = std::sin(advance);
  }
  Eigen::Vector3d dirs_lidar[vlp16::kLasers];
  Eigen::Vector3f origins[16], directions[16];
  RayHit hits[16];
  for (std::int64_t k = k0; k < k1; ++k) {
    const std::int64_t t_ns = k * vlp16::kSequencePeriodNs;
    const FrameKinematics lidar = trajectory_.frame(t_ns * 1e-9, T_body_lidar_);
    const Eigen::Matrix3d R = lidar.T_world_frame.rotationMatrix();
    const Eigen::Vector3d& p = lidar.T_world_frame.translation();
    // Azimuth: pi at t = 0, clockwise seen from above (the beam's y is -sin).
    const double turns = static_cast<double>(t_ns % revolution_ns_) / revolution_ns_;
    const double azimuth = M_PI + 2.0 * M_PI * turns;
    const double cos_az = std::cos(azimuth), sin_az = std::sin(azimuth);
    for (int id = 0; id < vlp16::kLasers; ++id) {
      const double delta = id * vlp16::kFiringIntervalNs * 1e-9;
      const double c = cos_az * cos_advance[id] - sin_az * sin_advance[id];
      const double s = sin_az * cos_advance[id] + cos_az * sin_advance[id];
      const Eigen::Vector3d d(cos_elevation[id] * c, -cos_elevation[id] * s, sin_elevation[id]);
      dirs_lidar[id] = d;
      // Pose at the firing time, to first order in delta (< 35 us; error < 1e-8 m).
      const Eigen::Vector3d d_world = R * (d + delta * lidar.omega_frame.cross(d));
      origins[id] = (p + delta * lidar.v_world).cast<float>();
      directions[id] = d_world.normalized().cast<float>();
    }
    caster_.cast16(origins, directions, static_cast<float>(spec_.max_range), hits);
    vlp16::FiringSequence* firing = nullptr;
    if (firings != nullptr) {
      firing = &firings->emplace_back();
      firing->t_ns = t_ns;
      firing->azimuth_deg = 180.0 + 360.0 * turns;
      if (firing->azimuth_deg >= 360.0) firing->azimuth_deg -= 360.0;
    }
    for (int id = 0; id < vlp16::kLasers; ++id) {
      const RayHit& hit = hits[id];
      if (!std::isfinite(hit.distance)) continue;
      if (noise_.dropout > 0.0 && rng.uniform() < noise_.dropout) continue;
      double range = hit.distance;
      double intensity = reflectivity_[hit.triangle] * (0.35 + 0.65 * hit.cos_incidence);
      if (noise_.range_sigma > 0.0) range += rng.normal() * noise_.range_sigma;
      if (noise_.intensity_sigma > 0.0) intensity += rng.normal() * noise_.intensity_sigma;
      if (noise_.quantize) range = std::round(range / 0.002) * 0.002;
      if (range < spec_.min_range || range > spec_.max_range) continue;
      ScanPoint point;
      point.p = (range * dirs_lidar[id]).cast<float>();
      point.intensity = static_cast<float>(std::clamp(std::round(intensity), 0.0, 255.0));
      point.time =
          static_cast<float>((t_ns + id * vlp16::kFiringIntervalNs - scan.stamp_ns) * 1e-9);
      point.ring = static_cast<std::uint16_t>(vlp16::ring(id));
      scan.points.push_back(point);
      if (firing != nullptr) {
        // The packet's 2 mm steps (exact when the ranges are quantized); a
        // range beyond what the 16-bit field holds (131 m) is a no-return there.
        const long steps = std::lround(range / vlp16::kDistanceStep);
        firing->distance[id] = static_cast<std::uint16_t>(steps <= 65535 ? steps : 0);
        firing->reflectivity[id] = static_cast<std::uint8_t>(point.intensity);
      }
    }
  }
  return scan;
}

}  // namespace storey::sim
