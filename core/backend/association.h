#pragma once
/// Association of a keyframe's SRPs with the global plane map (section V-B of
/// the reference paper): every landmark is predicted in the keyframe frame with
/// the best current pose estimate; a pair passes when the normal angle, the
/// distance difference and the Mahalanobis distance (fit covariance + pose
/// uncertainty) are within their gates. The SRPs are then matched jointly: each
/// hypothesis (every SRP to one of its candidates or to a new plane, no
/// landmark twice) is scored after solving for the small keyframe pose
/// correction it implies, so that one rotation must explain all normals at
/// once; a match that a hypothesis of nearly the same score contradicts is
/// ambiguous and not used (parallel walls of a corridor).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "backend/backend_config.h"
#include "backend/srp_extraction.h"

namespace storey::backend {

/// A landmark predicted in the keyframe frame (oriented like the landmark).
struct PlanePrediction {
  int landmark = -1;
  Eigen::Vector3d n_kf = Eigen::Vector3d::UnitZ();
  double d_kf = 0.0;     ///< [m]
  int observations = 0;  ///< keyframes that have seen it so far
  /// Tracked (AssociationConfig::track_distance): the landmark's newest view,
  /// moved into this keyframe by the odometry. An SRP farther than track_gate
  /// from it (at the SRP's centroid) is another surface, not this landmark.
  bool tracked = false;
  Eigen::Vector3d n_track_kf = Eigen::Vector3d::UnitZ();
  double d_track_kf = 0.0;  ///< [m]
};

enum class AssociationOutcome {
  kMatched,       ///< observation of an existing landmark
  kNewPlane,      ///< no landmark within the gates: becomes a new one
  kAmbiguous,     ///< two landmarks fit nearly as well: not used
  kNearExisting,  ///< outside the gates but too close to a confirmed landmark (seen by at least
                  ///< `confirmed_observations` keyframes) to be a new plane: not used
  kRoughFit,      ///< fit RMS above `max_rms_ratio` times the run's median (backend/fit_noise.h):
                  ///< not used (decided before the association)
  kCount
};
const char* toString(AssociationOutcome outcome);

/// Why candidate pairs (SRP, landmark) failed; counted over all pairs.
enum class GateReject { kFacing, kAngle, kDistance, kMahalanobis, kFaceChange, kCount };
const char* toString(GateReject reason);

struct SrpAssociation {
  AssociationOutcome outcome = AssociationOutcome::kNewPlane;
  int landmark = -1;   ///< matched landmark (kMatched)
  double chi2 = 0.0;   ///< Mahalanobis distance of the pair alone (kMatched)
  int candidates = 0;  ///< landmarks within all gates
};

struct AssociationResult {
  std::vector<SrpAssociation> srps;  ///< one per SRP, same order
  std::array<long, static_cast<std::size_t>(GateReject::kCount)> gate_rejects{};
  int hypotheses = 0;  ///< joint hypotheses scored
};

/// Associates `srps` (keyframe frame) with the predicted landmarks; `up_kf`
/// is the world's up direction in the keyframe frame (the predicted pose's),
/// which splits the pose uncertainty into tilt and yaw.
AssociationResult associate(const std::vector<DetectedPlane>& srps,
                            const std::vector<PlanePrediction>& predictions,
                            const AssociationConfig& config,
                            const Eigen::Vector3d& up_kf = Eigen::Vector3d::UnitZ());

}  // namespace storey::backend
