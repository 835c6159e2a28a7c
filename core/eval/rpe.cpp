#include "eval/rpe.h"

#include <cmath>

#include "common/error.h"

namespace storey::eval {

RpeResult relativePoseError(const AssociatedPoses& poses, double segment_length, int stride) {
  if (!(segment_length > 0.0) || !std::isfinite(segment_length))
    throw Error("eval: RPE segment length must be > 0 m");
  if (stride < 1) throw Error("eval: RPE stride must be >= 1");
  const std::size_t n = poses.matched();
  std::vector<double> distance(n, 0.0);  // true path length from the first stamp [m]
  for (std::size_t i = 1; i < n; ++i) {
    distance[i] =
        distance[i - 1] +
        (poses.T_world_gt[i].translation() - poses.T_world_gt[i - 1].translation()).norm();
  }
  std::vector<double> translation, rotation;
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; i += static_cast<std::size_t>(stride)) {
    if (j < i) j = i;
    while (j < n && distance[j] - distance[i] < segment_length) ++j;
    if (j == n) break;  // later starts cannot complete a segment either
    const double length = distance[j] - distance[i];
    const Pose T_gti_gtj = poses.T_world_gt[i].inverse() * poses.T_world_gt[j];
    const Pose T_esti_estj = poses.T_world_est[i].inverse() * poses.T_world_est[j];
    const Pose E = T_gti_gtj.inverse() * T_esti_estj;
    translation.push_back(100.0 * E.translation().norm() / length);
    rotation.push_back(E.angle() / length);
  }
  RpeResult result;
  result.segment_length = segment_length;
  result.translation_percent = errorStats(std::move(translation));
  result.rotation_per_metre = errorStats(std::move(rotation));
  return result;
}

}  // namespace storey::eval
