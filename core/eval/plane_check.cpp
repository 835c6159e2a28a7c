#include "eval/plane_check.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "export/planes_json.h"

namespace storey::eval {

std::size_t PlaneCheck::wrongNotDownWeighted() const {
  return static_cast<std::size_t>(std::count_if(
      wrong.begin(), wrong.end(), [](const WrongObservation& w) { return !w.down_weighted; }));
}

namespace {

/// The truth pose nearest to t (the keyframes are scans, stamped like the truth).
const Pose& truthAt(const Trajectory& gt, double t, double tolerance, const std::string& where) {
  const auto it = std::lower_bound(gt.begin(), gt.end(), t,
                                   [](const StampedPose& p, double x) { return p.time < x; });
  const StampedPose* best = nullptr;
  if (it != gt.end()) best = &*it;
  if (it != gt.begin() && (!best || t - std::prev(it)->time < best->time - t))
    best = &*std::prev(it);
  if (!best || std::abs(best->time - t) > tolerance)
    throw Error(where + ": no true pose within " + std::to_string(tolerance) +
                " s of t = " + std::to_string(t));
  return best->pose;
}

}  // namespace

PlaneCheck checkPlanes(const std::string& planes_path, const Trajectory& gt,
                       const PlaneCheckOptions& options) {
  if (!(options.max_offset > 0.0) || !(options.max_angle_deg > 0.0) ||
      !(options.max_time_difference >= 0.0) || !(options.tight_offset > 0.0))
    throw Error("eval: plane check limits must be positive");
  const PlaneMap planes = readPlanesJson(planes_path);
  if (gt.empty()) throw Error("eval: the true trajectory is empty");

  PlaneCheck result;
  result.max_offset = options.max_offset;
  result.max_angle_deg = options.max_angle_deg;
  result.tight_offset = options.tight_offset;
  std::vector<double> abs_offsets;  // of every observation
  const double cos_max = std::cos(options.max_angle_deg * M_PI / 180.0);
  for (const GlobalPlane& plane : planes.planes) {
    const std::string where = planes_path + ": plane " + std::to_string(plane.id);
    const Eigen::Vector3d n_plane = plane.normal_world.normalized();
    struct Placed {
      Eigen::Vector3d normal_world, centroid_world;
      int keyframe;
      bool outlier;
    };
    std::vector<Placed> placed;
    for (const PlaneObservation& o : plane.observations) {
      if (!o.time || !o.centroid_keyframe)
        throw Error(where +
                    ": an observation without time or centroid (planes.json of an "
                    "older version?)");
      const Pose& T_world_lidar = truthAt(gt, *o.time, options.max_time_difference, where);
      placed.push_back({T_world_lidar.rotation() * o.normal_keyframe,
                        T_world_lidar * *o.centroid_keyframe, o.keyframe, o.outlier});
    }
    ++result.planes;
    if (placed.empty()) continue;
    std::vector<double> offsets;
    for (const Placed& p : placed) offsets.push_back(n_plane.dot(p.centroid_world));
    std::vector<double> sorted = offsets;
    std::nth_element(sorted.begin(),
                     sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (std::size_t i = 0; i < placed.size(); ++i) {
      ++result.observations;
      result.down_weighted += placed[i].outlier;
      const double cos_angle = std::min(1.0, std::abs(placed[i].normal_world.dot(n_plane)));
      const double offset = offsets[i] - median;
      abs_offsets.push_back(std::abs(offset));
      result.beyond_tight_offset += std::abs(offset) > options.tight_offset;
      if (cos_angle < cos_max || std::abs(offset) > options.max_offset)
        result.wrong.push_back({plane.id, placed[i].keyframe, offset,
                                std::acos(cos_angle) * 180.0 / M_PI, placed[i].outlier});
    }
  }
  if (!abs_offsets.empty()) {
    std::sort(abs_offsets.begin(), abs_offsets.end());
    const auto at = [&](double q) {
      return abs_offsets[static_cast<std::size_t>(q * static_cast<double>(abs_offsets.size() - 1))];
    };
    result.offset_median = at(0.5);
    result.offset_p90 = at(0.9);
  }
  return result;
}

}  // namespace storey::eval
