#include "pipeline/pipeline.h"

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "backend/backend.h"
#include "backend/keyframe_rule.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/log.h"
#include "export/kitti.h"
#include "export/map_export.h"
#include "export/report_markdown.h"
#include "io/log_reader.h"
#include "map/map_builder.h"
#include "odometry/odometry.h"
#include "pipeline/run_report.h"

namespace storey {

namespace fs = std::filesystem;

PipelineResult runPipeline(const std::string& log_path, const Config& config,
                           const std::string& out_dir, const ProgressFn& progress) {
  config.validate();
  const auto wall_start = std::chrono::steady_clock::now();
  std::unique_ptr<LogReader> reader = openLog(log_path, config);
  logInfo("reading " + reader->describe());

  PipelineResult result;
  RunReportBuilder report(config);
  // The SRP back end (keyframes, plane constraints, graph) corrects the
  // odometry after each graph solve; off (--no-srp): trajectory = odometry
  // and the keyframes (for the map) follow the same rule on the odometry.
  std::unique_ptr<SrpBackend> backend;
  if (config.backend.srp) backend = std::make_unique<SrpBackend>(config);
  KeyframeSelector selector(config.backend.keyframes);
  // The map stage keeps the deskewed scans of the map (every graph keyframe
  // and the scans between them by the map's own spacing; on disk by
  // default); the newest scan is held too, as the last keyframe of the log.
  // Their final poses come from the final trajectory (scan index), and their
  // points are labelled with the graph keyframe whose part of the walk they are.
  std::unique_ptr<MapBuilder> map;
  if (config.map.enabled) map = std::make_unique<MapBuilder>(config.map);
  std::vector<std::size_t> map_scan_index;  // per map scan: index into the trajectory
  int keyframes = 0;
  std::size_t scans = 0;
  bool last_is_keyframe = false, last_in_map = false;
  Scan last_scan;
  StampedPose last_pose{};
  Pose T_world_last_map_scan;
  const double map_angle = config.map.scan_angle_deg * M_PI / 180.0;
  auto addToMap = [&](const Scan& deskewed, const Pose& T_world_lidar, std::size_t scan_index) {
    map->addKeyframeScan(static_cast<int>(map_scan_index.size()), deskewed, keyframes - 1);
    map_scan_index.push_back(scan_index);
    T_world_last_map_scan = T_world_lidar;
  };

  LidarInertialOdometry* front_end = nullptr;
  LidarInertialOdometry odometry(config, [&](OdometryResult&& scan) {
    report.addScan(scan);
    const StampedPose stamped{scan.deskewed.time(), scan.T_world_lidar};
    bool keyframe = false;
    if (backend) {
      const std::optional<Pose> correction = backend->addScan(scan);
      keyframe = backend->stats().keyframes > keyframes;
      if (correction) front_end->applyCorrection(*correction);
    } else {
      result.odometry.push_back(stamped);
      result.trajectory.push_back(stamped);
      keyframe = selector.accept(stamped.pose, stamped.time);
      if (keyframe) result.keyframes.push_back(stamped);
    }
    if (keyframe) ++keyframes;
    last_is_keyframe = keyframe;
    last_in_map = false;
    if (map) {
      const Pose step = T_world_last_map_scan.inverse() * stamped.pose;
      if (keyframe || step.translation().norm() > config.map.scan_spacing ||
          Eigen::AngleAxisd(step.rotation()).angle() > map_angle) {
        addToMap(scan.deskewed, stamped.pose, scans);
        last_in_map = true;
      }
      last_scan = std::move(scan.deskewed);
    }
    last_pose = stamped;
    ++scans;
  });
  front_end = &odometry;

  LogMessage message;
  std::int64_t messages = 0;
  while (reader->next(message)) {
    if (auto* scan = std::get_if<Scan>(&message)) {
      odometry.addScan(std::move(*scan));
    } else {
      odometry.addImu(std::get<ImuSample>(message));
    }
    if (progress && (++messages % 256) == 0) {
      const double fraction = reader->progress();
      if (!progress(fraction < 0.0 ? 0.0 : fraction, "odometry")) throw Cancelled();
    }
  }
  odometry.finish();
  if (result.odometry.empty() && (!backend || backend->stats().scans == 0)) {
    throw Error(log_path + ": no scan could be processed (" +
                std::to_string(reader->stats().scans) + " scans read)");
  }
  // The last scan is a keyframe too (the back end does the same), so the end
  // of the walk is in the map and constrained by the planes.
  if (backend) {
    if (progress && !progress(1.0, "back end: final optimisation")) throw Cancelled();
    backend->finish();
    result.odometry = backend->odometry();
    result.trajectory = backend->trajectory();
    result.keyframes = backend->keyframes();
    result.planes_json = backend->planesJson();
    report.setBackend(backend->stats());
  } else if (!last_is_keyframe) {
    result.keyframes.push_back(last_pose);
  }
  if (!last_is_keyframe) ++keyframes;
  if (map && !last_in_map) addToMap(last_scan, last_pose.pose, scans - 1);
  Scan().points.swap(last_scan.points);
  if (static_cast<int>(result.keyframes.size()) != keyframes || result.trajectory.size() != scans)
    throw Error("internal: " + std::to_string(result.keyframes.size()) + " keyframe poses for " +
                std::to_string(keyframes) + " keyframes, " +
                std::to_string(result.trajectory.size()) + " poses for " + std::to_string(scans) +
                " scans");

  const double wall_seconds_slam =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  report.setInput(log_path, reader->stats(), odometry.drops());
  report.setInitialisation(odometry.initialState());
  report.setTrajectory(result.trajectory);
  report.setWallTime(wall_seconds_slam);
  result.report_json = report.json();

  const fs::path out(out_dir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw Error(out_dir + ": cannot create the output folder: " + ec.message());

  // Map, storeys and their exports (each file atomically).
  if (map) {
    std::vector<Pose> T_world_lidar_per_map_scan;
    T_world_lidar_per_map_scan.reserve(map_scan_index.size());
    for (std::size_t s : map_scan_index)
      T_world_lidar_per_map_scan.push_back(result.trajectory[s].pose);
    std::vector<Eigen::Vector3d> keyframe_positions;  // MapCloud::keyframe labels = keyframes
    for (const StampedPose& k : result.keyframes) keyframe_positions.push_back(k.pose.translation());
    MapOutputs outputs = buildAndExportMap(*map, T_world_lidar_per_map_scan, keyframe_positions,
                                           config.storeys, out_dir, progress);
    map.reset();  // the keyframe scan store is no longer needed
    result.map = outputs.map;
    result.storeys = outputs.storeys;
    result.files = outputs.files;
    result.report_json = addMapToReport(result.report_json, outputs);
  }
  if (progress && !progress(1.0, "writing outputs")) throw Cancelled();

  auto write = [&](const std::string& name, auto&& writer) {
    writer((out / name).string());
    result.files.push_back(name);
  };
  write("odometry.tum", [&](const std::string& p) { writeTum(p, result.odometry); });
  write("trajectory.tum", [&](const std::string& p) { writeTum(p, result.trajectory); });
  write("trajectory_kitti.txt", [&](const std::string& p) {
    writeKitti(p, (out / "trajectory_kitti_times.txt").string(), result.trajectory);
  });
  result.files.push_back("trajectory_kitti_times.txt");
  write("keyframes.tum", [&](const std::string& p) { writeTum(p, result.keyframes); });
  if (backend)
    write("planes.json",
          [&](const std::string& p) { writeFileAtomically(p, result.planes_json + "\n"); });
  else
    fs::remove(out / "planes.json", ec);  // a previous run's would be mistaken for this one's

  // The report last, with the whole run's wall time and the file list.
  nlohmann::json report_json = nlohmann::json::parse(result.report_json);
  report_json["wall_time_s_total"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.files.push_back("report.json");
  result.files.push_back("report.md");
  report_json["files"] = result.files;
  result.report_json = report_json.dump(2);
  writeFileAtomically((out / "report.json").string(), result.report_json + "\n");
  writeReportMarkdown(result.report_json, (out / "report.md").string());
  return result;
}

}  // namespace storey
