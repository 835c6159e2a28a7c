#pragma once
/// Plane associations of a run checked against the true trajectory: every
/// observation in planes.json (a plane seen from one keyframe, in that
/// keyframe's LiDAR frame) is placed in the world with the keyframe's TRUE
/// pose. Observations of one global plane must then lie on one surface: an
/// observation whose centroid is more than `max_offset` from the median of
/// its plane's observations (measured along the plane's estimated normal), or
/// whose normal is more than `max_angle_deg` from it, was associated with the
/// wrong surface. Counted with whether the back end down-weighted it
/// (`outlier`): a wrong association that was not is one that survived the
/// robust loss. The distribution of every observation's |offset| (median,
/// 90th percentile, the number beyond `tight_offset`) shows the landmarks
/// that merged parallel surfaces a few centimetres apart (a door recess, a
/// pilaster), which `max_offset` is too wide to count (docs/evaluation.md).
#include <cstddef>
#include <string>
#include <vector>

#include "trajectory/tum.h"

namespace storey::eval {

struct PlaneCheckOptions {
  double max_offset = 0.1;            ///< centroid distance from its plane's median [m, > 0]
  double max_angle_deg = 5.0;         ///< normal angle to the plane's normal [deg, > 0]
  double max_time_difference = 0.01;  ///< observation stamp to truth stamp [s, >= 0]
  double tight_offset = 0.03;         ///< offsets beyond this are counted too [m, > 0]
};

struct WrongObservation {
  int plane = 0;           ///< the plane's id
  int keyframe = 0;        ///< the observation's keyframe
  double offset = 0.0;     ///< signed centroid offset from the plane's median [m]
  double angle_deg = 0.0;  ///< normal angle to the plane [deg]
  bool down_weighted = false;
};

struct PlaneCheck {
  std::size_t planes = 0, observations = 0;
  std::size_t down_weighted = 0;                 ///< observations the back end flagged `outlier`
  std::vector<WrongObservation> wrong;           ///< off their plane under the true poses
  double max_offset = 0.0, max_angle_deg = 0.0;  ///< the limits used
  /// |offset| of every observation from its plane's median [m]: median, 90th
  /// percentile; observations beyond `tight_offset` (the limit used).
  double offset_median = 0.0, offset_p90 = 0.0, tight_offset = 0.0;
  std::size_t beyond_tight_offset = 0;
  std::size_t wrongNotDownWeighted() const;
};

/// Reads planes.json (storey-planes format) and checks it; throws storey::Error
/// naming the file and the problem (unreadable, wrong format, an observation
/// without a truth pose within max_time_difference).
PlaneCheck checkPlanes(const std::string& planes_path, const Trajectory& gt,
                       const PlaneCheckOptions& options = {});

}  // namespace storey::eval
