#pragma once
/// The SRP back end (section V of the reference paper, docs/method/backend.md):
/// keyframes from the odometry, structural representative planes of each
/// keyframe's deskewed scan, their association with the global plane map, and
/// the keyframe graph (odometry relative poses + plane observations) solved
/// with Ceres whenever a plane constraint appears. After each solve the
/// odometry is moved into the corrected frame (the correction addScan
/// returns); at the end every scan's pose is the odometry pose corrected by
/// interpolating the corrections of the keyframes around it.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backend/association.h"
#include "backend/srp_extraction.h"
#include "config/config.h"
#include "odometry/odometry.h"
#include "trajectory/tum.h"

namespace storey {

/// Counts and timings of the back end (the run report shows them).
struct BackendStats {
  std::int64_t scans = 0;
  std::int64_t keyframes = 0;
  std::int64_t srps = 0;                ///< SRPs extracted over all keyframes
  std::int64_t keyframes_without_srp = 0;
  std::int64_t planes = 0;              ///< global plane landmarks
  std::int64_t observations = 0;        ///< plane observations in the graph
  std::array<std::int64_t, 4> outcomes{};  ///< per AssociationOutcome
  std::array<std::int64_t, static_cast<std::size_t>(backend::GateReject::kCount)> gate_rejects{};
  std::array<std::int64_t, static_cast<std::size_t>(backend::PlaneReject::kCount)> plane_rejects{};
  std::int64_t wrong_associations = 0;  ///< observations beyond outlier_chi2 after the final solve
                                        ///< (down-weighted by the robust loss)
  std::int64_t optimisations = 0, full_optimisations = 0;
  std::int64_t revisits = 0;  ///< keyframes that saw a plane again after more than a window
  // Wall-clock times per keyframe [ms]: extraction and association at every
  // keyframe, optimisation at the keyframes that ran one.
  std::vector<double> ms_extraction, ms_association, ms_optimisation;
  std::vector<double> ms_full_optimisation, ms_window_optimisation;  ///< the two kinds of solve
  std::vector<int> optimisation_keyframes;  ///< graph size at each optimisation
  double ms_final_optimisation = 0.0;
};

/// Checks the `backend:` values; throws storey::Error naming the key at fault.
void validateBackendConfig(const BackendConfig& config);

class SrpBackend {
 public:
  explicit SrpBackend(const Config& config);
  ~SrpBackend();
  SrpBackend(const SrpBackend&) = delete;
  SrpBackend& operator=(const SrpBackend&) = delete;

  /// One odometry result, in time order, in the odometry's current world
  /// frame. When the graph was optimised, returns T_corrected_old, which the
  /// caller must pass to LidarInertialOdometry::applyCorrection before the
  /// next result (results after it are expected in the corrected frame).
  std::optional<Pose> addScan(const OdometryResult& scan);
  /// Final solve of the whole graph and the wrong-association count.
  void finish();

  /// Final pose of the LiDAR for every scan (after finish()).
  Trajectory trajectory() const;
  /// The front end's own trajectory: the odometry with the corrections it
  /// was given taken out again (continuous; what it would be on its own).
  Trajectory odometry() const;
  /// Keyframe poses after optimisation.
  Trajectory keyframes() const;
  /// Global planes with their observations (OUT/planes.json).
  std::string planesJson() const;
  const BackendStats& stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace storey
