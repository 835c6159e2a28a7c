#include "map_dev.h"

#include <chrono>

#include "common/error.h"
#include "common/log.h"
#include "io/log_reader.h"
#include "odometry/odometry.h"

namespace storey::test {

DevRun runOdometryIntoMap(const std::string& log_path, const Config& config, MapBuilder& builder,
                          double keyframe_distance, double keyframe_angle_deg) {
  const auto wall_start = std::chrono::steady_clock::now();
  std::unique_ptr<LogReader> reader = openLog(log_path, config);
  DevRun run;
  RunReportBuilder report(config);
  const double max_angle = keyframe_angle_deg * 3.14159265358979323846 / 180.0;
  LidarInertialOdometry odometry(config, [&](OdometryResult&& scan) {
    const StampedPose stamped{scan.deskewed.time(), scan.T_world_lidar};
    run.trajectory.push_back(stamped);
    report.addScan(scan);
    bool keyframe = run.keyframe_poses.empty();
    if (!keyframe) {
      const Pose delta = run.keyframe_poses.back().inverse() * scan.T_world_lidar;
      keyframe = delta.translation().norm() > keyframe_distance || delta.angle() > max_angle;
    }
    if (keyframe) {
      builder.addKeyframeScan(static_cast<int>(run.keyframe_poses.size()), scan.deskewed);
      run.keyframe_poses.push_back(scan.T_world_lidar);
      run.keyframes.push_back(stamped);
    }
  });
  LogMessage message;
  while (reader->next(message)) {
    if (auto* scan = std::get_if<Scan>(&message))
      odometry.addScan(std::move(*scan));
    else
      odometry.addImu(std::get<ImuSample>(message));
  }
  odometry.finish();
  if (run.trajectory.empty()) throw Error(log_path + ": no scan could be processed");
  report.setInput(log_path, reader->stats(), odometry.drops());
  report.setInitialisation(odometry.initialState());
  report.setTrajectory(run.trajectory);
  report.setWallTime(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
  run.report_json = report.json();
  return run;
}

}  // namespace storey::test
