#include "export/kitti.h"

#include <cstdio>
#include <ostream>

#include "common/atomic_file.h"

namespace storey {

void writeKitti(const std::string& poses_path, const std::string& times_path,
                const Trajectory& trajectory) {
  writeFileAtomically(poses_path, [&](std::ostream& out) {
    char line[512];
    for (const StampedPose& s : trajectory) {
      const Eigen::Matrix3d R = s.pose.rotationMatrix();
      const Eigen::Vector3d& t = s.pose.translation();
      std::snprintf(line, sizeof(line),
                    "%.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e\n", R(0, 0),
                    R(0, 1), R(0, 2), t.x(), R(1, 0), R(1, 1), R(1, 2), t.y(), R(2, 0), R(2, 1),
                    R(2, 2), t.z());
      out << line;
    }
  });
  if (times_path.empty()) return;
  writeFileAtomically(times_path, [&](std::ostream& out) {
    char line[64];
    for (const StampedPose& s : trajectory) {
      std::snprintf(line, sizeof(line), "%.9f\n", s.time);
      out << line;
    }
  });
}

}  // namespace storey
