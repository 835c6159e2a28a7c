#include "sim/lidar_simulator.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "sim/random.h"

namespace storey::sim {
namespace {

constexpr int kRayPacket = 16;  ///< rays per Embree packet (RayCaster::cast16)

}  // namespace

LidarSimulator::LidarSimulator(const TriangleMesh& mesh, const Trajectory& trajectory,
                               const SensorsSpec& sensors, const LidarNoise& noise,
                               std::uint64_t seed)
    : trajectory_(trajectory),
      T_body_lidar_(sensors.T_body_lidar),
      spec_(sensors.lidar),
      beams_(lidarBeams(sensors.lidar.model)),
      noise_(noise),
      seed_(seed),
      revolution_ns_(static_cast<std::int64_t>(std::llround(1e9 / sensors.lidar.rotation_rate))),
      frame_id_(sensors.lidar_frame_id),
      caster_(mesh) {
  for (const Triangle& t : mesh.triangles()) reflectivity_.push_back(t.reflectivity);
  if (beams_.channels() % kRayPacket != 0)
    throw Error("simulator: a LiDAR model's beam count must be a multiple of 16");
}

int LidarSimulator::scanCount(double duration) const {
  const std::int64_t span = static_cast<std::int64_t>(std::floor(duration * 1e9));
  // Scan n is complete when its last firing is inside the span.
  int n = static_cast<int>(span / revolution_ns_);
  while (n > 0 && scanEndNs(n - 1) > span) --n;
  return n;
}

std::int64_t LidarSimulator::sequenceStartNs(std::int64_t k) const {
  if (beams_.sequence_period_ns > 0) return k * beams_.sequence_period_ns;
  const std::int64_t columns = beams_.columns;
  return (k * revolution_ns_ + columns / 2) /
         columns;  // nearest ns; column n * columns at n / rate
}

std::int64_t LidarSimulator::firstSequence(int n) const {
  if (beams_.sequence_period_ns <= 0) return static_cast<std::int64_t>(n) * beams_.columns;
  const std::int64_t start = n * revolution_ns_;
  return (start + beams_.sequence_period_ns - 1) / beams_.sequence_period_ns;
}

std::int64_t LidarSimulator::scanStampNs(int n) const {
  return sequenceStartNs(firstSequence(n));
}

std::int64_t LidarSimulator::scanEndNs(int n) const {
  return sequenceStartNs(firstSequence(n + 1) - 1) +
         *std::max_element(beams_.firing_ns.begin(), beams_.firing_ns.end());
}

Scan LidarSimulator::simulateScan(int n, std::vector<VelodyneFiring>* firings,
                                  OrganisedScan* organised) const {
  if (firings != nullptr && beams_.layout != CloudLayout::kVelodyne)
    throw Error(std::string("simulator: no Velodyne packets for the ") + toString(beams_.model));
  Random rng(seed_, 0x11da2000ULL + static_cast<std::uint64_t>(n));
  const int channels = beams_.channels();
  Scan scan;
  scan.frame_id = frame_id_;
  scan.stamp_ns = scanStampNs(n);
  const std::int64_t k0 = firstSequence(n), k1 = firstSequence(n + 1);
  scan.points.reserve(static_cast<std::size_t>((k1 - k0) * channels));
  if (firings != nullptr) {
    firings->clear();
    firings->reserve(static_cast<std::size_t>(k1 - k0));
  }
  if (organised != nullptr) {
    organised->rows = channels;
    organised->columns = static_cast<int>(k1 - k0);
    organised->cells.assign(static_cast<std::size_t>(channels * (k1 - k0)), OrganisedPoint{});
  }

  // Per channel: elevation sines/cosines and the azimuth advance since the
  // sequence's first firing (rotation until the channel fires, plus its
  // azimuth offset).
  std::vector<double> cos_elevation(channels), sin_elevation(channels);
  std::vector<double> cos_advance(channels), sin_advance(channels), delta(channels);
  for (int c = 0; c < channels; ++c) {
    cos_elevation[c] = std::cos(beams_.elevation[c]);
    sin_elevation[c] = std::sin(beams_.elevation[c]);
    const double advance =
        2.0 * M_PI * beams_.firing_ns[c] / revolution_ns_ + beams_.azimuth_offset[c];
    cos_advance[c] = std::cos(advance);
    sin_advance[c] = std::sin(advance);
    delta[c] = beams_.firing_ns[c] * 1e-9;
  }
  std::vector<Eigen::Vector3d> dirs_lidar(channels);
  std::vector<Eigen::Vector3f> origins(channels), directions(channels);
  std::vector<RayHit> hits(channels);
  const double step = beams_.distance_step;
  for (std::int64_t k = k0; k < k1; ++k) {
    const std::int64_t t_ns = sequenceStartNs(k);
    const FrameKinematics lidar = trajectory_.frame(t_ns * 1e-9, T_body_lidar_);
    const Eigen::Matrix3d R = lidar.T_world_frame.rotationMatrix();
    const Eigen::Vector3d& p = lidar.T_world_frame.translation();
    // Azimuth: pi at t = 0, clockwise seen from above (the beam's y is -sin).
    const double turns = static_cast<double>(t_ns % revolution_ns_) / revolution_ns_;
    const double azimuth = M_PI + 2.0 * M_PI * turns;
    const double cos_az = std::cos(azimuth), sin_az = std::sin(azimuth);
    for (int c = 0; c < channels; ++c) {
      const double co = cos_az * cos_advance[c] - sin_az * sin_advance[c];
      const double si = sin_az * cos_advance[c] + cos_az * sin_advance[c];
      const Eigen::Vector3d d(cos_elevation[c] * co, -cos_elevation[c] * si, sin_elevation[c]);
      dirs_lidar[c] = d;
      // Pose at the firing time, to first order in delta (< 40 us; error < 1e-8 m).
      const Eigen::Vector3d d_world = R * (d + delta[c] * lidar.omega_frame.cross(d));
      origins[c] = (p + delta[c] * lidar.v_world).cast<float>();
      directions[c] = d_world.normalized().cast<float>();
    }
    for (int c = 0; c < channels; c += kRayPacket) {
      caster_.cast16(&origins[c], &directions[c], static_cast<float>(spec_.max_range), &hits[c]);
    }
    VelodyneFiring* firing = nullptr;
    if (firings != nullptr) {
      firing = &firings->emplace_back();
      firing->t_ns = t_ns;
      firing->azimuth_deg = kScanStartAzimuthDeg + 360.0 * turns;
      if (firing->azimuth_deg >= 360.0) firing->azimuth_deg -= 360.0;
    }
    const std::int64_t column = k - k0;
    if (organised != nullptr) {
      for (int c = 0; c < channels; ++c) {
        organised->cells[static_cast<std::size_t>(c * organised->columns + column)].t_ns =
            static_cast<std::uint32_t>(t_ns - scan.stamp_ns);
      }
    }
    for (int c = 0; c < channels; ++c) {
      const RayHit& hit = hits[c];
      if (!std::isfinite(hit.distance)) continue;
      if (noise_.dropout > 0.0 && rng.uniform() < noise_.dropout) continue;
      double range = hit.distance;
      const float reflectivity = reflectivity_[hit.triangle];
      double intensity = reflectivity * (0.35 + 0.65 * hit.cos_incidence);
      if (noise_.range_sigma > 0.0) range += rng.normal() * noise_.range_sigma;
      if (noise_.intensity_sigma > 0.0) intensity += rng.normal() * noise_.intensity_sigma;
      if (noise_.quantize) range = std::round(range / step) * step;
      if (range < spec_.min_range || range > spec_.max_range) continue;
      ScanPoint point;
      point.p = (range * dirs_lidar[c]).cast<float>();
      point.intensity = static_cast<float>(std::clamp(std::round(intensity), 0.0, 255.0));
      point.time = static_cast<float>((t_ns + beams_.firing_ns[c] - scan.stamp_ns) * 1e-9);
      point.ring = beams_.ring[c];
      scan.points.push_back(point);
      if (firing != nullptr) {
        // The packet's distance steps (exact when the ranges are quantized); a
        // range beyond what the 16-bit field holds (131 m; VLP-32C 262 m) is a
        // no-return there.
        const long steps = std::lround(range / step);
        firing->distance[c] = static_cast<std::uint16_t>(steps <= 65535 ? steps : 0);
        firing->reflectivity[c] = static_cast<std::uint8_t>(point.intensity);
      }
      if (organised != nullptr) {
        OrganisedPoint& cell =
            organised->cells[static_cast<std::size_t>(c * organised->columns + column)];
        cell.p = point.p;
        cell.intensity = point.intensity;
        cell.reflectivity =
            static_cast<std::uint16_t>(std::clamp(std::round(reflectivity), 0.0f, 255.0f));
        cell.range_mm = static_cast<std::uint32_t>(std::lround(range * 1000.0));
      }
    }
  }
  return scan;
}

}  // namespace storey::sim
