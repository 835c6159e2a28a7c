// End-to-end runs of the LiDAR-inertial odometry on simulated logs with
// ground truth: the `tiny` preset as is, with the IMU mounted upside down
// and turned, at 200 Hz, and cut to start while walking.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "config/config.h"
#include "eval/association.h"
#include "eval/ate.h"
#include "io/log_reader.h"
#include "odometry/odometry.h"
#include "pipeline/pipeline.h"
#include "sim/simulator.h"
#include "support/temp_dir.h"
#include "trajectory/drift.h"

namespace storey {
namespace {

struct RunErrors {
  double ate_rmse = 0.0, ate_max = 0.0, rotation_max = 0.0;
  double end_drift = 0.0, max_step_error = 0.0;
  std::size_t scans = 0, gt_scans = 0;
  nlohmann::json report;
};

RunErrors simulateAndRun(const sim::BuildingSpec& spec,
                         const std::function<void(Config&)>& edit_config = {}) {
  test::TempDir dir;
  const std::string sim_dir = dir.file("sim");
  sim::SimulationOptions options;
  options.compress = false;
  sim::simulate(spec, options, sim_dir);
  Config config = loadRunConfig("", sim_dir + "/" + sim::kCalibrationFile);
  if (edit_config) edit_config(config);
  const PipelineResult result = runPipeline(sim_dir + "/" + sim::kBagFile, config, dir.file("out"));
  const Trajectory gt = readTum(sim_dir + "/" + sim::kLidarTruthFile);

  RunErrors errors;
  errors.scans = result.odometry.size();
  errors.gt_scans = gt.size();
  errors.report = nlohmann::json::parse(result.report_json);
  const eval::AssociatedPoses poses = eval::associate(gt, result.odometry);
  const eval::AteResult ate = eval::absoluteTrajectoryError(poses, eval::Alignment::kNone);
  errors.ate_rmse = ate.translation.rmse;
  errors.ate_max = ate.translation.max;
  errors.rotation_max = ate.rotation.max;
  errors.end_drift = endPointDrift(result.odometry).dxyz;
  // Jumps: the estimated motion between consecutive scans against the true one.
  for (std::size_t i = 1; i < poses.matched(); ++i) {
    const Eigen::Vector3d est_step =
        poses.T_world_est[i].translation() - poses.T_world_est[i - 1].translation();
    const Eigen::Vector3d gt_step =
        poses.T_world_gt[i].translation() - poses.T_world_gt[i - 1].translation();
    errors.max_step_error = std::max(errors.max_step_error, (est_step - gt_step).norm());
  }
  return errors;
}

void expectAccurate(const RunErrors& e) {
  EXPECT_GE(e.scans + 5, e.gt_scans) << "almost every scan gets a pose";
  EXPECT_LT(e.ate_rmse, 0.10) << "ATE RMSE [m]";
  EXPECT_LT(e.ate_max, 0.25) << "largest position error [m]";
  EXPECT_LT(e.rotation_max, 3.0 * M_PI / 180.0) << "largest rotation error [rad]";
  EXPECT_LT(e.end_drift, 0.10) << "end-point drift [m] (the walk returns to its start)";
  EXPECT_LT(e.max_step_error, 0.05) << "largest jump between consecutive scans [m]";
}

TEST(OdometryEndToEnd, TinyPresetStaysOnTheTruth) {
  const RunErrors e = simulateAndRun(sim::loadBuildingSpec("tiny"));
  expectAccurate(e);
  // The report carries timings and counts.
  const auto& odometry = e.report.at("odometry");
  const auto& timing = odometry.at("timing_ms");
  EXPECT_GT(timing.at("total_per_scan").at("median").get<double>(), 0.0);
  // The thread's CPU time: positive, and no more than its wall-clock time.
  const double cpu_ms = timing.at("total_per_scan_cpu").at("median").get<double>();
  EXPECT_GT(cpu_ms, 0.0);
  EXPECT_LE(cpu_ms, 1.01 * timing.at("total_per_scan").at("median").get<double>() + 0.05);
  // The back end's whole work per keyframe, wall clock and CPU.
  const auto& keyframe = e.report.at("backend").at("timing_ms_per_keyframe");
  EXPECT_GT(keyframe.at("total").at("median").get<double>(), 0.0);
  EXPECT_GT(keyframe.at("total_cpu").at("median").get<double>(), 0.0);
  EXPECT_GE(keyframe.at("total").at("median").get<double>(),
            keyframe.at("srp_extraction").at("median").get<double>());
  EXPECT_GT(odometry.at("matches_per_scan").at("point_to_plane").at("median").get<double>(), 100.0);
  EXPECT_TRUE(odometry.at("rejected_matches").is_object());
  EXPECT_TRUE(odometry.contains("degenerate_scans"));
  RecordProperty("ate_rmse_m", std::to_string(e.ate_rmse));
}

TEST(OdometryEndToEnd, AFeatureBudgetMatchesAtMostThatManyPlanesAndStaysOnTheTruth) {
  // odometry.max_matched_planes thins a scan's planar features evenly before
  // matching (a dense sensor's cost per scan); all of them still enter the map.
  const int budget = 150;
  const RunErrors e = simulateAndRun(sim::loadBuildingSpec("tiny"), [&](Config& config) {
    config.odometry.max_matched_planes = budget;
  });
  expectAccurate(e);
  const auto& odometry = e.report.at("odometry");
  EXPECT_GT(odometry.at("features_per_scan").at("planes").at("median").get<double>(), 2.0 * budget)
      << "the budget must bind on this log for the test to mean anything";
  EXPECT_LE(odometry.at("matches_per_scan").at("point_to_plane").at("max").get<double>(), budget);
  EXPECT_GT(odometry.at("matches_per_scan").at("point_to_plane").at("median").get<double>(),
            0.5 * budget);
}

TEST(OdometryEndToEnd, BothMarginalisationsStayOnTheTruth) {
  // odometry.marginalise_pose: the default runs in every other test; this one
  // runs the other setting (the oldest pose held fixed, or free under the
  // marginalised prior on the whole state).
  const bool other = !OdometryConfig().marginalise_pose;
  const RunErrors e = simulateAndRun(sim::loadBuildingSpec("tiny"), [&](Config& config) {
    config.odometry.marginalise_pose = other;
  });
  expectAccurate(e);
  EXPECT_LT(e.ate_rmse, 0.03) << "marginalise_pose " << other;
}

TEST(OdometryEndToEnd, ImuUpsideDownTurnedAt200Hz) {
  sim::BuildingSpec spec = sim::loadBuildingSpec("tiny");
  spec.sensors.imu.rate = 200.0;
  const Eigen::Quaterniond upside_down_turned =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()) *
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX());
  spec.sensors.T_body_imu = Pose(upside_down_turned, Eigen::Vector3d(0.05, -0.03, 0.02));
  spec.validate();
  expectAccurate(simulateAndRun(spec));
}

TEST(OdometryEndToEnd, ALogEndingInsideAScanDropsThatScan) {
  // Found by `storey bench` (random:2, a 200 Hz IMU): the last scan ended 6 us
  // after the last IMU sample, and the run stopped with an error. Now the
  // scans the IMU does not cover to their end are dropped and counted.
  test::TempDir dir;
  sim::SimulationOptions options;
  options.max_duration = 6.0;
  options.threads = 2;
  sim::simulate(sim::loadBuildingSpec("tiny"), options, dir.file("sim"));
  const Config config = loadRunConfig("", dir.file("sim/") + sim::kCalibrationFile);
  std::vector<LogMessage> messages;
  {
    const auto reader = openLog(dir.file("sim/") + sim::kBagFile, config.input, config.sensor);
    LogMessage message;
    while (reader->next(message)) messages.push_back(std::move(message));
  }
  std::int64_t last_scan_ns = 0;
  for (const LogMessage& m : messages)
    if (const auto* scan = std::get_if<Scan>(&m)) last_scan_ns = scan->stamp_ns;
  LidarInertialOdometry odometry(config.odometry, config.sensor);
  std::size_t results = 0, scans = 0;
  OdometryResult result;
  for (const LogMessage& m : messages) {
    if (const auto* scan = std::get_if<Scan>(&m)) {
      odometry.addScan(*scan);
      ++scans;
    } else if (std::get<ImuSample>(m).stamp_ns <= last_scan_ns + 50'000'000) {
      odometry.addImu(std::get<ImuSample>(m));  // the IMU ends half-way through the last scan
    }
    while (odometry.nextResult(result)) ++results;
  }
  ASSERT_NO_THROW(odometry.finish());
  while (odometry.nextResult(result)) ++results;
  const OdometryDrops& drops = odometry.drops();
  EXPECT_EQ(drops.after_last_imu, 1);
  // Every other scan has its result (or was dropped for another counted reason).
  EXPECT_EQ(results + static_cast<std::size_t>(drops.after_last_imu + drops.before_first_imu +
                                               drops.empty),
            scans);
  EXPECT_LE(static_cast<std::int64_t>(scans - results), 2);
}

TEST(OdometryEndToEnd, MovingStartWithoutMotionStartIsAClearError) {
  Config config;
  config.odometry.imu_init.motion_start = false;
  LidarInertialOdometry odometry(config.odometry, config.sensor);
  for (int i = 0; i < 800; ++i) {  // 2 s of a sensor spinning at 1 rad/s
    ImuSample s;
    s.stamp_ns = 1'000'000'000LL + i * 2'500'000LL;
    s.gyro = Eigen::Vector3d(0.0, 0.0, 1.0);
    s.accel = Eigen::Vector3d(0.0, 0.0, 9.81);
    try {
      odometry.addImu(s);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("not still"), std::string::npos) << e.what();
      return;
    }
  }
  FAIL() << "a log that does not start still must be rejected";
}

TEST(OdometryEndToEnd, MovingStartWithoutScansIsAClearError) {
  // In motion and no scan to initialise from: both reasons in one line.
  Config config;
  LidarInertialOdometry odometry(config.odometry, config.sensor);
  for (int i = 0; i < 1600; ++i) {
    ImuSample s;
    s.stamp_ns = 1'000'000'000LL + i * 2'500'000LL;
    s.gyro = Eigen::Vector3d(0.0, 0.0, 1.0);
    s.accel = Eigen::Vector3d(0.0, 0.0, 9.81);
    odometry.addImu(s);
  }
  try {
    odometry.finish();
    FAIL() << "no scans: the run cannot start";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("not still"), std::string::npos) << what;
    EXPECT_NE(what.find("initialising while moving failed"), std::string::npos) << what;
  }
}

TEST(OdometryEndToEnd, StartsWhileWalking) {
  // The tiny walk cut to start at 5 s, walking at about 0.8 m/s: gravity,
  // velocity and biases from the first 2 s of LiDAR and IMU.
  test::TempDir dir;
  const std::string sim_dir = dir.file("sim");
  sim::SimulationOptions options;
  options.compress = false;
  options.start_at = 5.0;
  sim::simulate(sim::loadBuildingSpec("tiny"), options, sim_dir);
  const Config config = loadRunConfig("", sim_dir + "/" + sim::kCalibrationFile);
  const PipelineResult result = runPipeline(sim_dir + "/" + sim::kBagFile, config, dir.file("out"));
  const nlohmann::json report = nlohmann::json::parse(result.report_json);
  const auto& init = report.at("imu_initialisation");
  ASSERT_EQ(init.at("start"), "moving") << init.dump();
  EXPECT_NEAR(init.at("moving").at("speed_m_s").get<double>(), 0.8, 0.1);
  EXPECT_NEAR(init.at("moving").at("gravity_found_m_s2").get<double>(), 9.81, 0.2);

  // Gravity's direction at the first scan against the truth's.
  const Trajectory imu_truth = readTum(sim_dir + "/" + sim::kImuTruthFile);
  const double t0 = result.odometry.front().time;
  const auto truth = std::min_element(imu_truth.begin(), imu_truth.end(), [&](auto& a, auto& b) {
    return std::abs(a.time - t0) < std::abs(b.time - t0);
  });
  const Eigen::Vector3d up_true = truth->pose.rotation().conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_est(init.at("up_in_imu_frame")[0].get<double>(),
                               init.at("up_in_imu_frame")[1].get<double>(),
                               init.at("up_in_imu_frame")[2].get<double>());
  EXPECT_LT(std::acos(std::min(1.0, up_true.dot(up_est))), 0.008) << "tilt [rad]";

  // The trajectory: every scan, no jump, within 1 cm of the truth (SE(3)-aligned).
  const Trajectory gt = readTum(sim_dir + "/" + sim::kLidarTruthFile);
  const eval::AssociatedPoses poses = eval::associate(gt, result.odometry);
  EXPECT_GE(result.odometry.size() + 3, gt.size());
  const eval::AteResult ate = eval::absoluteTrajectoryError(poses, eval::Alignment::kSe3);
  EXPECT_LT(ate.translation.rmse, 0.010);
  EXPECT_LT(ate.translation.max, 0.030);
  RecordProperty("ate_rmse_m", std::to_string(ate.translation.rmse));
}

}  // namespace
}  // namespace storey
