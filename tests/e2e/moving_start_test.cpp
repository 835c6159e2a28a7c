// Logs that start while moving (issue: real-world logs): `storey simulate
// --start-at` cuts a walk so that it starts mid-corridor, and `storey run`
// must initialise in motion (docs/method/odometry.md, "Starting in motion")
// and map it as well as the same walk with its still start; and the real
// HDL-32E capture (1.5 s from a moving vehicle, IMU in its position packets)
// must initialise and give a trajectory.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/run_storey.h"
#include "support/temp_dir.h"
#include "unit/io_pcap/real_data.h"

namespace storey {
namespace {

using test::shellQuoted;

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in, nullptr, false);
}

/// SE(3)-aligned ATE RMSE [m] of `est` against `gt` (storey eval).
double ateSe3(const test::TempDir& dir, const std::string& gt, const std::string& est) {
  const auto e =
      test::runStorey("eval --gt " + shellQuoted(gt) + " --est " + shellQuoted(est) + " --json -",
                      dir.path().string());
  EXPECT_EQ(e.exit_code, 0) << e.err;
  const nlohmann::json eval = nlohmann::json::parse(e.out, nullptr, false);
  if (!eval.is_discarded() && eval.contains("ate"))
    for (const auto& a : eval["ate"])
      if (a["alignment"] == "se3") return a["translation_m"]["rmse"].get<double>();
  ADD_FAILURE() << "no SE(3) ATE in: " << e.out;
  return 1e9;
}

/// The poses of a TUM file at or after time t [s], into a new file.
std::string posesFrom(const std::string& tum, double t, const std::string& out) {
  std::ifstream in(tum);
  std::ofstream o(out);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || std::stod(line) >= t - 1e-6) o << line << '\n';
  }
  return out;
}

TEST(MovingStart, MidCorridorStartMapsAsWellAsTheStillStart) {
  // The default preset's first minute: standing for 2 s, then the corridor.
  // Cut at 8 s, the log starts walking at about 0.8 m/s, 6 m down the corridor.
  test::TempDir dir;
  const std::string still = dir.file("still"), moving = dir.file("moving");
  for (const auto& [out, extra] :
       {std::pair{still, std::string()}, std::pair{moving, std::string(" --start-at 8")}}) {
    const auto s = test::runStorey(
        "simulate default --no-progress --duration 60 -o " + shellQuoted(out) + extra,
        dir.path().string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const auto r = test::runStorey("run " + shellQuoted(out + "/simulation.bag") +
                                       " --calibration " + shellQuoted(out + "/calibration.yaml") +
                                       " --no-render -o " + shellQuoted(out + "_out"),
                                   dir.path().string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const nlohmann::json report = readJson(moving + "_out/report.json");
  ASSERT_FALSE(report.is_discarded());
  const auto& init = report["imu_initialisation"];
  EXPECT_EQ(init["start"], "moving") << init.dump();
  EXPECT_NE(init["not_still"].get<std::string>().find("not still"), std::string::npos);
  EXPECT_EQ(readJson(still + "_out/report.json")["imu_initialisation"]["start"], "still");

  // Both over the same stretch of the walk (from 8 s), against its truth.
  const std::string truth = moving + "/groundtruth_lidar.tum";
  const double t_cut = 1'700'000'000.0 + 8.0;  // the simulator's clock starts at 1.7e9 s
  const double ate_still =
      ateSe3(dir, truth, posesFrom(still + "_out/trajectory.tum", t_cut, dir.file("s.tum")));
  const double ate_moving = ateSe3(dir, truth, moving + "_out/trajectory.tum");
  RecordProperty("ate_still_m", std::to_string(ate_still));
  RecordProperty("ate_moving_m", std::to_string(ate_moving));
  EXPECT_LT(ate_still, 0.05);
  EXPECT_LE(ate_moving, 1.5 * ate_still) << "still " << ate_still << " m, moving " << ate_moving;
}

TEST(MovingStart, RealHdl32eCaptureFromAMovingVehicleInitialises) {
  const std::string pcap = test::realData("veloview-hdl32e-imu/monterey-first-100-packets.pcap");
  if (!std::filesystem::exists(pcap)) GTEST_SKIP() << "real data absent: " << pcap;
  test::TempDir dir;
  const auto r = test::runStorey(
      "run " + shellQuoted(pcap) + " --no-render -o " + shellQuoted(dir.file("out")),
      dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = readJson(dir.file("out/report.json"));
  ASSERT_FALSE(report.is_discarded());
  const auto& init = report["imu_initialisation"];
  EXPECT_EQ(init["start"], "moving") << init.dump();
  // Its README: a low-grade IMU with a gyro bias of about -29 deg/s on one
  // axis (z here) and gravity visible in the accelerometers.
  EXPECT_NEAR(init["gyro_bias_rad_s"][2].get<double>(), -29.0 * M_PI / 180.0, 0.05);
  EXPECT_NEAR(init["moving"]["gravity_found_m_s2"].get<double>(), 9.81, 0.8);
  // A pose for (almost) every scan the IMU covers, and the slow motion the
  // README describes (the scene shifts about 0.15 m in 1.3 s).
  std::ifstream tum(dir.file("out/trajectory.tum"));
  std::string line;
  int poses = 0;
  while (std::getline(tum, line))
    if (!line.empty() && line[0] != '#') ++poses;
  EXPECT_GE(poses, 14);
  EXPECT_LT(report["end_point_drift"]["path_length_m"].get<double>(), 1.0);
}

}  // namespace
}  // namespace storey
