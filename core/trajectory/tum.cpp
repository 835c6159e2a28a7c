#include "trajectory/tum.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"

namespace storey {

void writeTum(const std::string& path, const Trajectory& trajectory) {
  writeFileAtomically(path, [&](std::ostream& out) {
    char line[256];
    for (const StampedPose& s : trajectory) {
      const Eigen::Vector3d& t = s.pose.translation();
      const Eigen::Quaterniond& q = s.pose.rotation();
      std::snprintf(line, sizeof(line), "%.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", s.time, t.x(),
                    t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
      out << line;
    }
  });
}

Trajectory readTum(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open trajectory file");
  Trajectory trajectory;
  std::string text;
  int line_number = 0;
  while (std::getline(in, text)) {
    ++line_number;
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream fields(text);
    double v[8];
    for (double& x : v) {
      if (!(fields >> x) || !std::isfinite(x)) {
        throw Error(path + " line " + std::to_string(line_number) +
                    ": expected 8 finite numbers 't x y z qx qy qz qw'");
      }
    }
    std::string extra;
    if (fields >> extra)
      throw Error(path + " line " + std::to_string(line_number) + ": more than 8 values");
    if (!trajectory.empty() && v[0] <= trajectory.back().time)
      throw Error(path + " line " + std::to_string(line_number) + ": time " + std::to_string(v[0]) +
                  " does not increase");
    try {
      trajectory.push_back(
          {v[0], Pose(Eigen::Quaterniond(v[7], v[4], v[5], v[6]), Eigen::Vector3d(v[1], v[2], v[3]))});
    } catch (const Error& e) {
      throw Error(path + " line " + std::to_string(line_number) + ": " + e.what());
    }
  }
  return trajectory;
}

}  // namespace storey
