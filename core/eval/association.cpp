#include "eval/association.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/error.h"

namespace storey::eval {

void AssociationOptions::validate() const {
  if (!(max_time_difference >= 0.0) || !std::isfinite(max_time_difference))
    throw Error("eval: max_time_difference must be >= 0 s");
  if (!(max_interpolation_gap > 0.0) || !std::isfinite(max_interpolation_gap))
    throw Error("eval: max_interpolation_gap must be > 0 s");
}

Pose interpolatePose(const StampedPose& a, const StampedPose& b, double t) {
  const double span = b.time - a.time;
  const double s = span > 0.0 ? std::clamp((t - a.time) / span, 0.0, 1.0) : 0.0;
  const Eigen::Vector3d p = (1.0 - s) * a.pose.translation() + s * b.pose.translation();
  return Pose(a.pose.rotation().slerp(s, b.pose.rotation()), p);
}

namespace {

std::string spanText(const Trajectory& trajectory) {
  if (trajectory.empty()) return "no poses";
  char buffer[128];
  std::snprintf(buffer, sizeof(buffer), "%zu poses, t = %.6f .. %.6f s", trajectory.size(),
                trajectory.front().time, trajectory.back().time);
  return buffer;
}

}  // namespace

TruthCoverage truthAt(const Trajectory& gt, double t, const AssociationOptions& options,
                      Pose& T_world_gt) {
  const double tol = options.max_time_difference;
  if (gt.empty() || t < gt.front().time - tol || t > gt.back().time + tol)
    return TruthCoverage::kOutsideSpan;
  // First truth pose at or after t (the truth is strictly increasing in time).
  const auto after = std::lower_bound(gt.begin(), gt.end(), t,
                                      [](const StampedPose& s, double x) { return s.time < x; });
  if (after == gt.begin()) {
    T_world_gt = gt.front().pose;  // at or just before the first truth pose
  } else if (after == gt.end()) {
    T_world_gt = gt.back().pose;  // just after the last truth pose
  } else {
    const StampedPose& a = *(after - 1);
    const StampedPose& b = *after;
    if (b.time - a.time <= options.max_interpolation_gap) {
      T_world_gt = interpolatePose(a, b, t);
    } else if (t - a.time <= tol) {
      T_world_gt = a.pose;
    } else if (b.time - t <= tol) {
      T_world_gt = b.pose;
    } else {
      return TruthCoverage::kInGap;
    }
  }
  return TruthCoverage::kCovered;
}

AssociatedPoses associate(const Trajectory& gt, const Trajectory& est,
                          const AssociationOptions& options) {
  options.validate();
  AssociatedPoses result;
  result.est_poses = est.size();
  for (const StampedPose& e : est) {
    Pose T_world_gt;
    switch (truthAt(gt, e.time, options, T_world_gt)) {
      case TruthCoverage::kOutsideSpan: ++result.outside_gt_span; continue;
      case TruthCoverage::kInGap: ++result.in_gt_gap; continue;
      case TruthCoverage::kCovered: break;
    }
    result.times.push_back(e.time);
    result.T_world_gt.push_back(T_world_gt);
    result.T_world_est.push_back(e.pose);
  }
  if (result.matched() < 2) {
    throw Error(
        "eval: only " + std::to_string(result.matched()) +
        " estimated poses have ground truth at their time (need 2); estimate: " + spanText(est) +
        "; ground truth: " + spanText(gt) + " (are both stamped with the same clock?)");
  }
  return result;
}

}  // namespace storey::eval
