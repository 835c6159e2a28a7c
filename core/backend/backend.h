#pragma once
/// The back end's interface (section V of the reference paper,
/// docs/method/backend.md): it takes the odometry's scans one by one, in time
/// order, decides which become keyframes, and returns its best pose for each;
/// finish() returns the final trajectory, keyframes and plane map. Two
/// implementations: the SRP back end (srp_backend.h; keyframes, structural
/// representative planes, keyframe graph) and the odometry-only back end
/// (odometry_backend.h; `--no-srp`, the same keyframe rule, trajectory =
/// odometry). Data flow is one way: nothing goes back to the odometry.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "backend/association.h"
#include "backend/backend_config.h"
#include "backend/srp_extraction.h"
#include "trajectory/tum.h"
#include "types/plane_map.h"
#include "types/pose.h"
#include "types/scan.h"

namespace storey {

/// Counts and timings of the SRP back end (the run report shows them).
struct BackendStats {
  std::int64_t scans = 0;
  std::int64_t keyframes = 0;
  std::int64_t srps = 0;  ///< SRPs extracted over all keyframes
  std::int64_t keyframes_without_srp = 0;
  std::int64_t planes = 0;        ///< global plane landmarks
  std::int64_t observations = 0;  ///< plane observations in the graph
  std::array<std::int64_t, static_cast<std::size_t>(backend::AssociationOutcome::kCount)>
      outcomes{};  ///< per AssociationOutcome
  std::array<std::int64_t, static_cast<std::size_t>(backend::GateReject::kCount)> gate_rejects{};
  std::array<std::int64_t, static_cast<std::size_t>(backend::PlaneReject::kCount)> plane_rejects{};
  std::int64_t wrong_associations = 0;  ///< observations beyond outlier_chi2 after the final solve
                                        ///< (down-weighted by the robust loss)
  /// Views of level surfaces left out of the final solve as tilted
  /// (GraphConfig::level_view_max_tilt_deg); also among wrong_associations.
  std::int64_t tilted_level_views = 0;
  std::int64_t optimisations = 0, full_optimisations = 0;
  std::int64_t revisits = 0;  ///< keyframes that saw a plane again after more than a window
  // Wall-clock times per keyframe [ms]: extraction and association at every
  // keyframe, optimisation at the keyframes that ran one.
  std::vector<double> ms_extraction, ms_association, ms_optimisation;
  // The whole of each keyframe's work (extraction, association, graph
  // update and solve): wall clock and the back end thread's CPU time [ms].
  std::vector<double> ms_keyframe, cpu_ms_keyframe;
  std::vector<double> ms_full_optimisation, ms_window_optimisation;  ///< the two kinds of solve
  std::vector<int> optimisation_keyframes;  ///< graph size at each optimisation
  double ms_final_optimisation = 0.0;
  double srp_rms_median = 0.0;  ///< median fit RMS of all SRPs (the rough-fit gate's scale) [m]
};

/// What the back end decided for one scan.
struct BackendDecision {
  bool keyframe = false;  ///< the scan is a keyframe (a graph vertex; always in the map)
  /// The back end's current best pose of the scan: the odometry pose moved by
  /// the latest graph correction (= the odometry pose with the back end off).
  Pose T_world_lidar;
};

/// Everything the back end knows at the end of the log.
struct SlamResult {
  /// The front end's pose of the LiDAR per scan, levelled by its last
  /// gravity estimate (one levelling for the whole log).
  Trajectory odometry;
  Trajectory trajectory;  ///< final pose per scan (= odometry with the back end off)
  /// Keyframes at their final poses; the last scan of the log is always the
  /// last keyframe (so the end of the walk is in the map and constrained).
  Trajectory keyframes;
  std::optional<PlaneMap> planes;     ///< global SRPs; absent with the back end off
  std::optional<BackendStats> stats;  ///< SRP back end only
};

class Backend {
 public:
  virtual ~Backend() = default;
  /// One odometry result, in time order: the scan's reference time [s], the
  /// odometry's pose of the LiDAR in its own rigid map frame, the current
  /// levelling of that frame (world = q_world_odom odom; it changes as the
  /// odometry's gravity estimate improves, so a back end composes poses in
  /// the odometry frame and levels them once) and the scan deskewed to that
  /// time (LiDAR frame).
  virtual BackendDecision addScan(double time, const Pose& T_odom_lidar,
                                  const Eigen::Quaterniond& q_world_odom, const Scan& deskewed) = 0;
  /// End of the log: the last scan (the one given to the last addScan,
  /// `last_deskewed`) becomes a keyframe if it is not one yet; final solve.
  /// The back end keeps no copy of a scan that is no keyframe.
  virtual SlamResult finish(const Scan& last_deskewed) = 0;
};

/// The SRP back end when config.srp, else the odometry-only one. The config
/// is validated (storey::Error naming the key at fault).
std::unique_ptr<Backend> makeBackend(const BackendConfig& config);

}  // namespace storey
