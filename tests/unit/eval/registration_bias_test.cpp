// The registration-bias measurement on the simulator's `tiny` building: at
// the true poses the step is noise; a true pose moved by a known offset is
// found with that offset; a truth on another clock is an error that says so.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "common/error.h"
#include "config/config.h"
#include "eval/registration_bias.h"
#include "io/log_reader.h"
#include "support/run_storey.h"
#include "support/tiny_simulation.h"
#include "trajectory/tum.h"

namespace storey::eval {
namespace {

class RegistrationBias : public test::TinySimulation {
 protected:
  static RegistrationBiasResult measure(const Trajectory& truth) {
    const Config config = simConfig();
    const auto log = openLog(bag(), config.input, config.sensor);
    return measureRegistrationBias(*log, truth, config.odometry);
  }
  static Trajectory truth() { return readTum(simFile(sim::kLidarTruthFile)); }
};

TEST_F(RegistrationBias, AtTheTruePosesTheStepIsOnlyNoise) {
  const RegistrationBiasResult r = measure(truth());
  ASSERT_GT(r.steps.size(), 50u);
  EXPECT_LE(r.scans_without_truth, 1u);  // the last revolution may end after the truth
  // The map holds a scan once it would have left the odometry's window.
  EXPECT_LE(r.scans_without_map, static_cast<std::size_t>(simConfig().odometry.window_size));
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(r.mean_dp(i)), 0.004) << i;
  EXPECT_LT(r.median_abs_dz, 0.004);
  // The split by plane class adds up to the whole vertical step.
  for (const RegistrationStep& s : r.steps) {
    double sum = 0.0;
    for (double dz : s.class_dz) sum += dz;
    ASSERT_NEAR(sum, s.dp.z(), 1e-9);
    ASSERT_GT(s.matches, 0);
  }
}

TEST_F(RegistrationBias, APoseMovedUpIsPulledBackDown) {
  // Poses k and k + 1 moved up by 5 cm: scan k (its revolution runs from
  // stamp k to stamp k + 1) is deskewed right but sits 5 cm above the map of
  // the scans before it. Scan k - 1 ends at the moved pose k and is deskewed
  // wrong, so the clean reference is scan k - 2.
  Trajectory moved = truth();
  ASSERT_GT(moved.size(), 60u);
  const std::size_t k = moved.size() / 2;
  for (std::size_t i = k; i <= k + 1; ++i) {
    const Pose T = moved[i].pose;
    moved[i].pose = Pose(T.rotation(), T.translation() + Eigen::Vector3d(0.0, 0.0, 0.05));
  }
  const RegistrationBiasResult r = measure(moved);
  const RegistrationStep* at_k = nullptr;
  const RegistrationStep* clean = nullptr;
  for (const RegistrationStep& s : r.steps) {
    if (std::abs(s.time - moved[k].time) < 1e-4) at_k = &s;
    if (std::abs(s.time - moved[k - 2].time) < 1e-4) clean = &s;
  }
  ASSERT_NE(at_k, nullptr);
  ASSERT_NE(clean, nullptr);
  EXPECT_NEAR(at_k->dp.z(), -0.05, 0.01);
  EXPECT_LT(std::abs(clean->dp.z()), 0.01);
  ASSERT_FALSE(r.worst_windows.empty());
  for (std::size_t i = 1; i < r.worst_windows.size(); ++i)
    EXPECT_GE(std::abs(r.worst_windows[i - 1].mean_dz), std::abs(r.worst_windows[i].mean_dz));
}

TEST_F(RegistrationBias, WithTheImuTruthEveryPointHasItsOwnTruePose) {
  const Config config = simConfig();
  const Trajectory lidar_truth = truth();
  const Trajectory imu_truth = readTum(simFile(sim::kImuTruthFile));
  RegistrationBiasOptions options;
  options.imu_truth = &imu_truth;
  options.T_imu_lidar = config.sensor.T_imu_lidar;
  const auto log = openLog(bag(), config.input, config.sensor);
  const RegistrationBiasResult r =
      measureRegistrationBias(*log, lidar_truth, config.odometry, options);
  const RegistrationBiasResult coarse = measure(lidar_truth);
  // The same scans (the IMU truth may also cover the last revolution) at the
  // same poses from both truths.
  ASSERT_GE(r.steps.size(), coarse.steps.size());
  ASSERT_LE(r.steps.size(), coarse.steps.size() + 1);
  for (std::size_t i = 0; i < coarse.steps.size(); ++i) {
    ASSERT_EQ(r.steps[i].time, coarse.steps[i].time) << i;
    ASSERT_LT((r.steps[i].position_true - coarse.steps[i].position_true).norm(), 1e-3) << i;
  }
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(r.mean_dp(i)), 0.004) << i;
  EXPECT_LT(r.median_abs_dz, 0.004);

  // A calibration that is not the walk's is named, not measured as a bias.
  options.T_imu_lidar =
      Pose(config.sensor.T_imu_lidar.rotation(),
           config.sensor.T_imu_lidar.translation() + Eigen::Vector3d(0.0, 0.0, 0.05));
  const auto again = openLog(bag(), config.input, config.sensor);
  try {
    measureRegistrationBias(*again, lidar_truth, config.odometry, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("T_imu_lidar"), std::string::npos) << e.what();
  }
}

TEST_F(RegistrationBias, ATruthOnAnotherClockIsAnError) {
  Trajectory shifted = truth();
  for (StampedPose& p : shifted) p.time += 1000.0;
  try {
    measure(shifted);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("clock"), std::string::npos) << e.what();
  }
}

TEST_F(RegistrationBias, WritesOneCsvLinePerScan) {
  const RegistrationBiasResult r = measure(truth());
  const std::string path = file("bias.csv");
  writeRegistrationBiasCsv(path, r);
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("time,since_start,x_true", 0), 0u);
  std::size_t lines = 0;
  while (std::getline(in, line)) ++lines;
  EXPECT_EQ(lines, r.steps.size());
  EXPECT_NE(registrationBiasTable(r).find("scans evaluated"), std::string::npos);
}

TEST_F(RegistrationBias, RunsAsAProgramAndNamesABadTruthFile) {
  const std::string calibration = test::shellQuoted(simFile(sim::kCalibrationFile));
  const test::RunResult ok = test::runStorey(
      "registration-bias " + test::shellQuoted(bag()) + " --gt " +
          test::shellQuoted(simFile(sim::kLidarTruthFile)) + " --calibration " + calibration +
          " --from 2 --to 4 --csv " + test::shellQuoted(file("cli.csv")) + " --storeys " +
          test::shellQuoted(simFile(sim::kStoreysFile)) + " --gt-imu " +
          test::shellQuoted(simFile(sim::kImuTruthFile)),
      file(""));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("scans evaluated 2"), std::string::npos) << ok.out;  // 20 or 21 scans
  EXPECT_NE(ok.out.find("split by the true storeys"), std::string::npos) << ok.out;
  EXPECT_TRUE(std::ifstream(file("cli.csv")).good());

  const std::string missing = file("no_such_truth.tum");
  const test::RunResult bad =
      test::runStorey("registration-bias " + test::shellQuoted(bag()) + " --gt " +
                          test::shellQuoted(missing) + " --calibration " + calibration,
                      file(""));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("no_such_truth.tum"), std::string::npos) << bad.err;
}

// The split by the true storeys, on made-up steps: floors at 0 and 3 m, a
// walk carried 1.4 m above its floor, with a climb between them.
RegistrationStep stepAt(double z, double dz) {
  RegistrationStep s;
  s.position_true = Eigen::Vector3d(0.0, 0.0, z);
  s.dp = Eigen::Vector3d(0.0, 0.0, dz);
  s.class_dz = {dz, 0.0, 0.0, 0.0};
  return s;
}

TEST(RegistrationBiasSplit, HeightIsAboveTheHighestFloorBelowTheLidar) {
  const std::vector<double> floors = {6.0, -1.4, 2.3};  // any order
  EXPECT_DOUBLE_EQ(heightAboveFloor(0.0, floors), 1.4);
  EXPECT_DOUBLE_EQ(heightAboveFloor(2.3, floors), 3.7);  // a floor at the LiDAR is not below it
  EXPECT_NEAR(heightAboveFloor(7.5, floors), 1.5, 1e-12);
  EXPECT_TRUE(std::isnan(heightAboveFloor(-2.0, floors)));
  EXPECT_TRUE(std::isnan(heightAboveFloor(1.0, {})));
}

TEST(RegistrationBiasSplit, ScansBetweenTheStoreysWalkingHeightsAreOnTheStairs) {
  RegistrationBiasResult r;
  for (int i = 0; i < 10; ++i) r.steps.push_back(stepAt(1.4 + 0.01 * (i % 3), 0.001));  // storey 0
  for (int i = 0; i < 10; ++i) r.steps.push_back(stepAt(4.4 - 0.01 * (i % 3), 0.003));  // storey 1
  const double climb[] = {1.7, 2.2, 2.9, 3.1, 3.9};  // flights and a half landing
  for (double z : climb) r.steps.push_back(stepAt(z, 0.02));
  r.steps.push_back(stepAt(-0.5, 0.02));  // no floor below: not on a storey
  stairsSplit(r, {0.0, 3.0}, 0.15);
  ASSERT_TRUE(r.split);
  EXPECT_NEAR(r.walking_height, 1.4, 0.011);
  EXPECT_EQ(r.on_storeys.scans, 20u);
  EXPECT_EQ(r.on_stairs.scans, 6u);
  EXPECT_NEAR(r.on_storeys.mean_dp.z(), 0.002, 1e-12);
  EXPECT_NEAR(r.on_stairs.mean_dp.z(), 0.02, 1e-12);
  EXPECT_NEAR(r.on_stairs.class_mean_dz[0], 0.02, 1e-12);
  EXPECT_NEAR(r.on_stairs.median_abs_dz, 0.02, 1e-12);
  for (std::size_t i = 0; i < r.steps.size(); ++i) EXPECT_EQ(r.steps[i].on_stairs, i >= 20) << i;
  EXPECT_NE(registrationBiasTable(r).find("on stairs       6 scans, mean dz +0.0200 m"),
            std::string::npos)
      << registrationBiasTable(r);
}

TEST(RegistrationBiasSplit, WithoutFloorsNothingIsSplitAndTheCsvColumnIsEmpty) {
  RegistrationBiasResult r;
  r.steps = {stepAt(1.0, 0.0), stepAt(2.0, 0.0)};
  stairsSplit(r, {}, 0.15);
  EXPECT_FALSE(r.split);
  EXPECT_EQ(registrationBiasTable(r).find("split by"), std::string::npos);
  const std::string path = testing::TempDir() + "/registration_bias_split.csv";
  writeRegistrationBiasCsv(path, r);
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.substr(header.rfind(',') + 1), "on_stairs");
  std::getline(in, line);
  EXPECT_EQ(line.back(), ',');  // the column is there, empty
  stairsSplit(r, {0.0}, 0.15);
  writeRegistrationBiasCsv(path, r);
  std::ifstream again(path);
  std::getline(again, header);
  std::getline(again, line);
  EXPECT_EQ(line.substr(line.rfind(',') + 1), "0");  // the first one sets the usual height
}

}  // namespace
}  // namespace storey::eval
