// storey_map_dev LOG CALIBRATION OUT [CONFIG [GT.tum]]: odometry + the map stage, the
// outputs `storey run` will write once the lead integrates the map stage
// (trajectory.tum, keyframes.tum, trajectory_kitti.txt + times, map.*,
// storeys/, storeys.json, report.json, report.md). Prints peak memory.
// With GT.tum (the simulator's groundtruth_lidar.tum) the map stage runs a
// second time into OUT/gt_poses/ with the keyframes at their true poses: the
// map stage measured apart from the odometry's drift.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "config/calibration.h"
#include "export/kitti.h"
#include "export/map_export.h"
#include "export/report_markdown.h"
#include "map_dev.h"
#include "storeys/storey_segmentation.h"

namespace {

/// Pose of `truth` at time t: linear in position, slerp in rotation.
storey::Pose interpolate(const storey::Trajectory& truth, double t) {
  auto it = std::lower_bound(truth.begin(), truth.end(), t,
                             [](const storey::StampedPose& s, double v) { return s.time < v; });
  if (it == truth.begin()) return it->pose;
  if (it == truth.end()) return truth.back().pose;
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double u = (t - a.time) / (b.time - a.time);
  return storey::Pose(a.pose.rotation().slerp(u, b.pose.rotation()),
                      (1 - u) * a.pose.translation() + u * b.pose.translation());
}

double peakRssMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}


/// Reads a map.ply as exportMap writes it (33-byte records).
storey::MapCloud readOwnPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line) && line != "end_header")
    if (line.rfind("element vertex ", 0) == 0) n = std::stoull(line.substr(15));
  storey::MapCloud cloud;
  std::vector<char> r(33);
  for (std::size_t i = 0; i < n && in.read(r.data(), 33); ++i) {
    float xyz[4];
    double t;
    std::int32_t kf;
    std::memcpy(xyz, r.data(), 16);
    std::memcpy(&t, r.data() + 16, 8);
    std::memcpy(&kf, r.data() + 24, 4);
    cloud.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
    cloud.intensity.push_back(xyz[3]);
    cloud.time.push_back(t);
    cloud.keyframe.push_back(kf);
    cloud.storey.push_back(storey::kNoStorey);
    cloud.flags.push_back(0);
  }
  return cloud;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace storey;
  if (argc == 4 && std::string(argv[1]) == "--segment") {
    // storey_map_dev --segment MAP.ply KEYFRAMES.tum: the storey stage alone.
    MapCloud map = readOwnPly(argv[2]);
    std::vector<Eigen::Vector3d> positions;
    for (const StampedPose& k : readTum(argv[3])) positions.push_back(k.pose.translation());
    const Config config;
    const StoreySegmentation seg = segmentStoreys(map, positions, config.storeys);
    const auto& st = seg.stats;
    std::cerr << "regions " << st.regions << " floor cand " << st.floor_candidates
              << " ceiling cand " << st.ceiling_candidates << " slabs " << st.floor_slabs
              << " small " << st.slabs_too_small << " close " << st.slabs_too_close
              << " stair cells " << st.stair_cells << "; normals " << st.seconds_normals
              << " s, regions " << st.seconds_regions << " s\n";
    for (const StoreyInfo& s : seg.storeys)
      std::cerr << "storey " << s.index << " floor " << s.floor_elevation << " ceiling "
                << (s.ceiling_elevation ? std::to_string(*s.ceiling_elevation) : "-") << " area "
                << s.footprint_area << " points " << s.points << " stairs " << s.stair_points
                << "\n";
    return 0;
  }
  if (argc < 4) {
    std::cerr << "usage: storey_map_dev LOG CALIBRATION OUT [CONFIG]\n";
    return 2;
  }
  try {
    const std::string out = argv[3];
    Config config = loadRunConfig(argc > 4 ? argv[4] : "", argv[2]);
    const std::string gt_path = argc > 5 ? argv[5] : "";
    std::filesystem::create_directories(out);
    MapBuilder builder(config.map);
    const auto t0 = std::chrono::steady_clock::now();
    test::DevRun run = test::runOdometryIntoMap(argv[1], config, builder);
    const double odo_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double rss_odometry = peakRssMiB();
    std::cerr << "odometry: " << run.trajectory.size() << " scans, " << run.keyframe_poses.size()
              << " keyframes, " << odo_s << " s; keyframe store "
              << builder.stats().stored_bytes / 1048576.0 << " MiB; peak RSS " << rss_odometry
              << " MiB\n";
    writeTum(out + "/trajectory.tum", run.trajectory);
    writeTum(out + "/keyframes.tum", run.keyframes);
    writeKitti(out + "/trajectory_kitti.txt", out + "/trajectory_kitti_times.txt", run.trajectory);
    const MapOutputs outputs =
        buildAndExportMap(builder, run.keyframe_poses, config.storeys, out);
    const std::string report = addMapToReport(run.report_json, outputs);
    writeFileAtomically(out + "/report.json", report + "\n");
    writeReportMarkdown(report, out + "/report.md");
    std::cerr << "map: " << outputs.map_points << " points; build " << outputs.seconds_build
              << " s, storeys " << outputs.seconds_storeys << " s (normals "
              << outputs.segmentation.seconds_normals << ", regions "
              << outputs.segmentation.seconds_regions << "), export " << outputs.seconds_export
              << " s; peak RSS " << peakRssMiB() << " MiB (after odometry " << rss_odometry
              << ")\n";
    for (const StoreyInfo& s : outputs.storeys)
      std::cerr << "storey " << s.index << " floor " << s.floor_elevation << " ceiling "
                << (s.ceiling_elevation ? std::to_string(*s.ceiling_elevation) : "-") << " area "
                << s.footprint_area << " points " << s.points << " stairs " << s.stair_points
                << "\n";
    if (!gt_path.empty()) {
      const Trajectory truth = readTum(gt_path);
      std::vector<Pose> poses;
      for (const StampedPose& k : run.keyframes) poses.push_back(interpolate(truth, k.time));
      const MapOutputs gt = buildAndExportMap(builder, poses, config.storeys, out + "/gt_poses");
      std::cerr << "map at true keyframe poses: " << gt.map_points << " points, peak RSS "
                << peakRssMiB() << " MiB\n";
      for (const StoreyInfo& s : gt.storeys)
        std::cerr << "storey " << s.index << " floor " << s.floor_elevation << " ceiling "
                  << (s.ceiling_elevation ? std::to_string(*s.ceiling_elevation) : "-")
                  << " area " << s.footprint_area << " points " << s.points << " stairs "
                  << s.stair_points << "\n";
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "storey_map_dev: " << e.what() << "\n";
    return 1;
  }
}
