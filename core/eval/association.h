#pragma once
/// Pairs an estimated trajectory with ground truth by timestamp. For every
/// estimated pose at time t the ground truth is interpolated at t (linear in
/// position, slerp in rotation) between the two truth poses around t, so the
/// truth may have any rate. An estimated pose is left out, with a reason, when
/// t lies outside the truth's time span (beyond a tolerance) or inside a gap
/// of the truth longer than `max_interpolation_gap`.
#include <cstddef>
#include <vector>

#include "trajectory/tum.h"

namespace storey::eval {

struct AssociationOptions {
  /// An estimate this close to a truth stamp (or to the ends of the truth) takes
  /// that truth pose even where interpolation is not possible [s, >= 0].
  double max_time_difference = 0.01;
  /// Longest interval between two truth poses that is interpolated [s, > 0].
  double max_interpolation_gap = 0.5;
  void validate() const;  ///< storey::Error naming the bad field
};

/// Matched pairs, in the estimate's time order, and why the others were dropped.
struct AssociatedPoses {
  std::vector<double> times;        ///< the estimate's stamps [s]
  std::vector<Pose> T_world_gt;     ///< truth at each stamp
  std::vector<Pose> T_world_est;    ///< estimate at each stamp
  std::size_t est_poses = 0;        ///< poses in the estimate
  std::size_t outside_gt_span = 0;  ///< dropped: before the first / after the last truth pose
  std::size_t in_gt_gap = 0;        ///< dropped: between truth poses further apart than the gap
  std::size_t matched() const { return times.size(); }
};

/// Interpolates between a (at a.time) and b (at b.time) at time t; t is
/// clamped to [a.time, b.time].
Pose interpolatePose(const StampedPose& a, const StampedPose& b, double t);

/// Where a time falls with respect to the truth.
enum class TruthCoverage { kCovered, kOutsideSpan, kInGap };

/// The truth at time t as associate() takes it: interpolated between the two
/// truth poses around t, or the nearest one within `max_time_difference`
/// where that is not possible (the ends, a gap longer than
/// `max_interpolation_gap`). Writes T_world_gt only when kCovered.
TruthCoverage truthAt(const Trajectory& gt, double t, const AssociationOptions& options,
                      Pose& T_world_gt);

/// Associates `est` with `gt`. Throws storey::Error when fewer than 2 poses match,
/// with the two time spans in the message (a time offset between the files, for
/// example relative versus absolute stamps, is the usual cause).
AssociatedPoses associate(const Trajectory& gt, const Trajectory& est,
                          const AssociationOptions& options = {});

}  // namespace storey::eval
