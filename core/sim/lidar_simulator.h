#pragma once
/// Spinning-LiDAR simulation (the models of sim/lidar_model.h): every beam is
/// ray-cast from the sensor pose at its own firing time, so scans are
/// motion-distorted like real ones.
/// Velodyne: firing sequence k fires at k * period from the start of the
/// simulation (VLP-16 and VLP-32C 55.296 us, HDL-32E 46.08 us); a scan holds
/// the sequences starting in one revolution [n / rate, (n + 1) / rate) and its
/// stamp is the time of its first firing (the driver's stamp with
/// timestamp_first_packet). Ouster: column k fires every beam at once at
/// round(k / (columns * rate)); scan n is columns [n, n + 1) * columns and is
/// stamped with its first column (n / rate). Per-point times are in [0, 1 / rate).
/// Azimuth: pi (straight back) at t = 0, turning clockwise seen from above,
/// so every scan starts at kScanStartAzimuthDeg.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/building_spec.h"
#include "sim/lidar_model.h"
#include "sim/organised_scan.h"
#include "sim/raycaster.h"
#include "sim/trajectory.h"
#include "sim/velodyne_firing.h"
#include "types/scan.h"

namespace storey::sim {

/// The azimuth at which the head is at t = 0 and so where every Velodyne scan
/// starts [deg] (straight back); the packets' cut angle that gives the same
/// scans (input.velodyne_cut_angle_deg).
inline constexpr double kScanStartAzimuthDeg = 180.0;

struct LidarNoise {
  double range_sigma = 0.0;      ///< [m]
  double dropout = 0.0;          ///< probability [0, 1)
  double intensity_sigma = 0.0;  ///< [sensor units]
  bool quantize = false;  ///< report ranges in the sensor's steps (LidarBeams::distance_step)
};

class LidarSimulator {
 public:
  /// Simulates sensors.lidar.model (storey::Error when it has no model).
  LidarSimulator(const TriangleMesh& mesh, const Trajectory& trajectory, const SensorsSpec& sensors,
                 const LidarNoise& noise, std::uint64_t seed);

  const LidarBeams& beams() const { return beams_; }
  /// Number of complete revolutions within [0, duration].
  int scanCount(double duration) const;
  /// Stamp of scan n relative to the start of the simulation [ns].
  std::int64_t scanStampNs(int n) const;
  /// Time the driver would publish scan n (its last firing) [ns].
  std::int64_t scanEndNs(int n) const;
  /// Simulates scan n; Scan::stamp_ns is relative to the start of the
  /// simulation (add the start time). Thread-safe; deterministic per (seed, n).
  /// Scan::points are the returns in firing order, ring 0 = lowest beam.
  /// `firings` (optional; Velodyne models only, else storey::Error) receives
  /// the scan's firing sequences as the sensor reports them (no-returns as
  /// distance 0, times relative to the start of the simulation): the same
  /// returns as the scan's points, for a Velodyne capture of the log.
  /// `organised` (optional) receives every beam of every column, no-returns included.
  Scan simulateScan(int n, std::vector<VelodyneFiring>* firings = nullptr,
                    OrganisedScan* organised = nullptr) const;

 private:
  std::int64_t firstSequence(int n) const;
  std::int64_t sequenceStartNs(std::int64_t k) const;
  const Trajectory& trajectory_;
  Pose T_body_lidar_;
  LidarSpec spec_;
  LidarBeams beams_;
  LidarNoise noise_;
  std::uint64_t seed_;
  std::int64_t revolution_ns_;
  std::string frame_id_;
  std::vector<float> reflectivity_;  ///< per mesh triangle
  RayCaster caster_;
};

}  // namespace storey::sim
