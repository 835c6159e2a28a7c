#include "unit/eval/eval_fixtures.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace storey::test::eval {

std::string makeTempDir(const std::string& name) {
  static std::atomic<int> counter{0};
  const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
  std::ostringstream dir_name;
  dir_name << "storey_eval_" << name << "_" << ::getpid() << "_" << now << "_" << counter++;
  const auto dir = std::filesystem::temp_directory_path() / dir_name.str();
  std::filesystem::create_directories(dir);
  return dir.string();
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Pose yawPose(double yaw, const Eigen::Vector3d& p) {
  return Pose(Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())), p);
}

Trajectory wigglyWalk(int n, double t0) {
  Trajectory walk;
  for (int i = 0; i < n; ++i) {
    const double s = 0.1 * i;
    const Eigen::Vector3d p(3.0 * std::sin(0.3 * s) + 0.5 * s, 2.0 * std::cos(0.2 * s), 0.05 * s);
    const Eigen::Quaterniond q =
        Eigen::AngleAxisd(0.3 * s, Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(0.05 * std::sin(s), Eigen::Vector3d::UnitY()) *
        Eigen::AngleAxisd(0.04 * std::cos(1.3 * s), Eigen::Vector3d::UnitX());
    walk.push_back({t0 + s, Pose(q, p)});
  }
  return walk;
}

}  // namespace storey::test::eval
