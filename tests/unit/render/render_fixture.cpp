#include "render_fixture.h"

#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace storey::test {
namespace {

template <typename T>
void put(std::ofstream& out, T value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

struct Surface {
  Eigen::Vector3d n;  // world, Hesse n.x = d
  double d;
  Eigen::Vector3d facing;
  std::vector<Eigen::Vector3d> corners;  // world rectangle
};

struct Keyframe {
  Eigen::Quaterniond q;
  Eigen::Vector3d t;
};

}  // namespace

void writeMapPly(const std::string& path, const std::vector<MapPoint>& points) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\ncomment test map\nelement vertex " << points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\n"
         "property double time\nproperty int keyframe\nproperty int storey\nproperty uchar stairs\n"
         "end_header\n";
  for (const MapPoint& m : points) {
    put<float>(out, m.p.x());
    put<float>(out, m.p.y());
    put<float>(out, m.p.z());
    put<float>(out, 100.0f);
    put<double>(out, 1.0);
    put<std::int32_t>(out, m.keyframe);
    put<std::int32_t>(out, m.storey);
    put<std::uint8_t>(out, m.stairs ? 1 : 0);
  }
}

int writeRoomRun(const std::string& dir) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const double X = 4.0, Y = 3.0, H = 2.6;
  auto rect = [](Eigen::Vector3d a, Eigen::Vector3d b, Eigen::Vector3d c, Eigen::Vector3d d) {
    return std::vector<Eigen::Vector3d>{a, b, c, d};
  };
  using V = Eigen::Vector3d;
  const std::vector<Surface> surfaces = {
      {V(0, 0, 1), 0.0, V(0, 0, 1),
       rect(V(-X, -Y, 0), V(X, -Y, 0), V(X, Y, 0), V(-X, Y, 0))},  // 0 floor
      {V(-1, 0, 0), X, V(1, 0, 0),
       rect(V(-X, -Y, 0), V(-X, Y, 0), V(-X, Y, H), V(-X, -Y, H))},  // 1 wall x=-4
      {V(1, 0, 0), X, V(-1, 0, 0),
       rect(V(X, -Y, 0), V(X, Y, 0), V(X, Y, H), V(X, -Y, H))},  // 2 wall x=+4
      {V(0, 1, 0), Y, V(0, -1, 0),
       rect(V(-X, Y, 0), V(X, Y, 0), V(X, Y, H), V(-X, Y, H))},  // 3 wall y=+3
      {V(0, -1, 0), Y, V(0, 1, 0),
       rect(V(-X, -Y, 0), V(X, -Y, 0), V(X, -Y, H), V(-X, -Y, H))},  // 4 wall y=-3
      {V(0, 0, 1), H, V(0, 0, -1),
       rect(V(-X, -Y, H), V(X, -Y, H), V(X, Y, H), V(-X, Y, H))},  // 5 ceiling
  };
  const std::vector<Keyframe> keyframes = {
      {Eigen::Quaterniond::Identity(), V(-1.0, 0.0, 0.8)},
      {Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, V::UnitZ())), V(1.5, 0.5, 0.8)},
  };
  const std::vector<std::vector<int>> seen = {{0, 1, 3, 4}, {0, 2, 3, 5}};  // planes per keyframe

  // Map: a 10 cm grid on every surface (ceiling included).
  std::vector<MapPoint> map;
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    const auto& c = surfaces[s].corners;
    const V e1 = c[1] - c[0], e2 = c[3] - c[0];
    const int n1 = static_cast<int>(e1.norm() / 0.1), n2 = static_cast<int>(e2.norm() / 0.1);
    for (int i = 0; i <= n1; ++i)
      for (int j = 0; j <= n2; ++j) {
        const V p = c[0] + e1 * (static_cast<double>(i) / n1) + e2 * (static_cast<double>(j) / n2);
        map.push_back({p.cast<float>(), p.x() < 0.0 ? 0 : 1, 0, false});
      }
  }
  writeMapPly((fs::path(dir) / "map.ply").string(), map);

  // keyframes.tum, trajectory.tum (a line from the first keyframe to the second).
  auto tumLine = [](double t, const V& p, const Eigen::Quaterniond& q) {
    char buf[256];
    std::snprintf(buf, sizeof(buf), "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", t, p.x(), p.y(),
                  p.z(), q.x(), q.y(), q.z(), q.w());
    return std::string(buf);
  };
  {
    std::ofstream k(fs::path(dir) / "keyframes.tum");
    k << "# t x y z qx qy qz qw\n";
    for (std::size_t i = 0; i < keyframes.size(); ++i)
      k << tumLine(100.0 + 5.0 * i, keyframes[i].t, keyframes[i].q);
    std::ofstream t(fs::path(dir) / "trajectory.tum");
    for (int i = 0; i <= 50; ++i) {
      const double a = i / 50.0;
      t << tumLine(100.0 + 0.1 * i, (1 - a) * keyframes[0].t + a * keyframes[1].t,
                   keyframes[0].q.slerp(a, keyframes[1].q));
    }
  }

  // planes.json with hulls and centroids in each keyframe's LiDAR frame.
  nlohmann::json planes = nlohmann::json::array();
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    const Surface& surface = surfaces[s];
    nlohmann::json observations = nlohmann::json::array();
    for (std::size_t k = 0; k < keyframes.size(); ++k) {
      if (std::find(seen[k].begin(), seen[k].end(), static_cast<int>(s)) == seen[k].end()) continue;
      const Eigen::Matrix3d R = keyframes[k].q.toRotationMatrix();
      const V t = keyframes[k].t;
      V n = R.transpose() * surface.n;
      double d = surface.d - surface.n.dot(t);
      if (d < 0) n = -n, d = -d;
      nlohmann::json hull = nlohmann::json::array();
      V centroid = V::Zero();
      for (const V& c : surface.corners) {
        const V l = R.transpose() * (c - t);
        hull.push_back({l.x(), l.y(), l.z()});
        centroid += l / 4.0;
      }
      observations.push_back({{"keyframe", k},
                              {"time", 100.0 + 5.0 * k},
                              {"normal", {n.x(), n.y(), n.z()}},
                              {"distance", d},
                              {"points", 1000},
                              {"fit_rms_m", 0.01},
                              {"residual_chi2", 0.1},
                              {"outlier", false},
                              {"centroid", {centroid.x(), centroid.y(), centroid.z()}},
                              {"hull", hull}});
    }
    planes.push_back({{"id", s},
                      {"normal", {surface.n.x(), surface.n.y(), surface.n.z()}},
                      {"distance", surface.d},
                      {"facing", {surface.facing.x(), surface.facing.y(), surface.facing.z()}},
                      {"observation_count", observations.size()},
                      {"observations", observations}});
  }
  std::ofstream(fs::path(dir) / "planes.json") << nlohmann::json{
      {"format", "storey planes, version 1"},
      {"keyframes", keyframes.size()},
      {"planes", planes}}.dump(1);

  nlohmann::json storey = {{"index", 0},
                           {"floor_elevation", 0.0},
                           {"ceiling_elevation", H},
                           {"clear_height", H},
                           {"height", nullptr},
                           {"area", 48.0},
                           {"floor_area_detected", 45.0},
                           {"points", map.size()},
                           {"stair_points", 0},
                           {"footprint", {{-X, -Y}, {X, -Y}, {X, Y}, {-X, Y}}}};
  std::ofstream(fs::path(dir) / "storeys.json")
      << nlohmann::json{{"format", "storey-storeys"}, {"version", 1}, {"storeys", {storey}}}.dump(
             1);
  std::ofstream(fs::path(dir) / "report.json")
      << nlohmann::json{{"storey_version", "0.1.0"}, {"odometry", {{"scans", 51}}}}.dump(1);
  return static_cast<int>(surfaces.size());
}

}  // namespace storey::test
