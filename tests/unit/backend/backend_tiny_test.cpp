// End to end on the simulator's `tiny` building: simulate, run the pipeline
// with and without the SRP back end, compare both with the simulator's truth.
// Also checks the outputs (keyframes.tum, planes.json, report) and that every
// plane association is right when judged with the true keyframe poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "config/config.h"
#include "eval/evaluation.h"
#include "pipeline/pipeline.h"
#include "sim/simulator.h"
#include "support/tiny_simulation.h"
#include "trajectory/drift.h"
#include "types/plane.h"

namespace storey {
namespace {

class BackendTiny : public test::TinySimulation {
 protected:
  static Config config(bool srp) {
    Config c = simConfig();
    c.backend.srp = srp;
    return c;
  }
};

TEST_F(BackendTiny, OptimisedTrajectoryIsAccurateAndOutputsAreComplete) {
  const std::string out = file("out_srp");
  const PipelineResult r = runPipeline(bag(), config(true), out);
  const Trajectory gt = readTum(simFile(sim::kLidarTruthFile));
  ASSERT_EQ(r.trajectory.size(), r.odometry.size());

  const eval::TrajectoryEvaluation e = eval::evaluateTrajectory(gt, r.trajectory);
  const eval::TrajectoryEvaluation e_odo = eval::evaluateTrajectory(gt, r.odometry);
  const double ate = e.ateWith(eval::Alignment::kYawTranslation).translation.rmse;
  const double ate_rot = e.ateWith(eval::Alignment::kYawTranslation).rotation.rmse;
  std::cout << "tiny: ATE (yaw + translation aligned) " << ate << " m, " << ate_rot
            << " rad; odometry " << e_odo.ateWith(eval::Alignment::kYawTranslation).translation.rmse
            << " m; end-point drift " << e.est_drift.dxyz << " m " << e.est_drift.dangle
            << " rad (odometry " << e_odo.est_drift.dxyz << " m " << e_odo.est_drift.dangle
            << " rad)\n";
  EXPECT_LT(ate, 0.05);
  EXPECT_LT(ate_rot, 0.01);
  EXPECT_LT(e.est_drift.dxyz, 0.05);
  EXPECT_LT(e.est_drift.dangle, 0.02);

  // No jump in the output: consecutive scans move less than the robot can in 0.1 s.
  for (std::size_t i = 1; i < r.trajectory.size(); ++i) {
    const Pose step = r.trajectory[i - 1].pose.inverse() * r.trajectory[i].pose;
    ASSERT_LT(step.translation().norm(), 0.25) << i;
    ASSERT_LT(step.angle(), 0.2) << i;
  }

  // Outputs.
  for (const char* f :
       {"trajectory.tum", "odometry.tum", "keyframes.tum", "planes.json", "report.json"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / f)) << f;
  const Trajectory keyframes = readTum(out + "/keyframes.tum");
  EXPECT_GE(keyframes.size(), 7u);  // 9.4 m walked, a keyframe per metre
  std::ifstream report_file(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(report_file);
  EXPECT_EQ(report["backend"]["keyframes"].get<std::size_t>(), keyframes.size());
  const int reported_wrong = report["backend"]["association"]["wrong_associations"].get<int>();
  EXPECT_TRUE(report["table_ii_mean_median_ms"].contains("srp_extraction_per_keyframe"));

  // Every plane observation checked against the truth: the observed plane,
  // placed with the true keyframe pose, lies on the plane its other
  // observations agree on (normal within 3 deg of their mean, distance
  // within 0.1 m of their median).
  std::ifstream planes_file(out + "/planes.json");
  const nlohmann::json planes = nlohmann::json::parse(planes_file);
  auto truePose = [&](double t) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < gt.size(); ++i)
      if (std::abs(gt[i].time - t) < std::abs(gt[best].time - t)) best = i;
    return gt[best].pose;
  };
  int observations = 0, wrong = 0, wrong_not_flagged = 0, flagged = 0;
  for (const auto& plane : planes["planes"]) {
    const auto& obs = plane["observations"];
    ASSERT_FALSE(obs.empty());
    std::vector<Plane> world;
    for (const auto& o : obs) {
      const Eigen::Vector3d n(o["normal"][0].get<double>(), o["normal"][1].get<double>(),
                              o["normal"][2].get<double>());
      const Plane p_kf(n, o["distance"].get<double>());
      world.push_back(p_kf.transformed(truePose(o["time"].get<double>())));
    }
    std::vector<double> offsets;  // signed along the first normal
    for (const Plane& p : world)
      offsets.push_back(p.normal().dot(world[0].normal()) > 0 ? p.distance() : -p.distance());
    std::vector<double> sorted = offsets;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();  // oriented like the first
    for (const Plane& p : world)
      mean_normal +=
          p.normal().dot(world[0].normal()) > 0 ? p.normal() : Eigen::Vector3d(-p.normal());
    mean_normal.normalize();
    for (std::size_t i = 0; i < world.size(); ++i) {
      ++observations;
      const double angle =
          std::acos(std::clamp(std::abs(world[i].normal().dot(mean_normal)), 0.0, 1.0));
      const bool outlier = obs[i]["outlier"].get<bool>();
      flagged += outlier;
      if (angle > 3.0 * M_PI / 180.0 || std::abs(offsets[i] - median) > 0.1) {
        ++wrong;
        if (!outlier) ++wrong_not_flagged;
      }
    }
  }
  std::cout << "tiny: " << planes["planes"].size() << " planes, " << observations
            << " observations, " << wrong << " wrong by the truth, " << flagged
            << " down-weighted\n";
  EXPECT_GT(observations, 20);
  // No wrong association survives the robust loss (tiny has none at all);
  // the report counts what planes.json flags, a small share of the observations.
  EXPECT_EQ(wrong_not_flagged, 0);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(reported_wrong, flagged);
  EXPECT_LE(flagged, observations / 10);
}

TEST_F(BackendTiny, RoughFitsTakeNoPartInTheAssociation) {
  // A ratio just above 1: after the first 20 SRPs, those fitted worse than
  // the median of the SRPs before them are left out; every SRP still has
  // exactly one outcome.
  Config c = config(true);
  c.backend.association.max_rms_ratio = 1.0001;
  const std::string out = file("out_rough");
  const PipelineResult r = runPipeline(bag(), c, out);
  ASSERT_FALSE(r.trajectory.empty());
  std::ifstream in(std::filesystem::path(out) / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& association = report.at("backend").at("association");
  const int srps = report.at("backend").at("srps").get<int>();
  ASSERT_GT(srps, 21);
  int outcomes = 0;
  for (const auto& [name, count] : association.at("outcomes").items()) outcomes += count.get<int>();
  EXPECT_EQ(outcomes, srps);
  EXPECT_GE(association.at("outcomes").at("rough_fit").get<int>(), 1);
  EXPECT_LE(association.at("outcomes").at("rough_fit").get<int>(), srps - 20);
}

TEST_F(BackendTiny, TiltedViewsOfLevelSurfacesLeaveTheFinalSolve) {
  // A gate no view of a floor exceeds changes nothing: the same trajectory
  // as with the gate off.
  Config no_gate = config(true);
  no_gate.backend.graph.level_view_max_tilt_deg = 0.0;
  const PipelineResult off = runPipeline(bag(), no_gate, file("out_tilt_off"));
  Config wide = config(true);
  wide.backend.graph.level_view_max_tilt_deg = 30.0;
  const std::string out_wide = file("out_tilt_wide");
  const PipelineResult r_wide = runPipeline(bag(), wide, out_wide);
  ASSERT_EQ(r_wide.trajectory.size(), off.trajectory.size());
  for (std::size_t i = 0; i < off.trajectory.size(); ++i)
    ASSERT_EQ(r_wide.trajectory[i].pose.translation(), off.trajectory[i].pose.translation()) << i;
  std::ifstream wide_report(std::filesystem::path(out_wide) / "report.json");
  EXPECT_EQ(nlohmann::json::parse(wide_report)["backend"]["association"]["tilted_level_views"], 0);

  // A gate every real view exceeds (no fit is level to 1e-6 deg): every
  // view of a floor or ceiling is left out, flagged in planes.json and
  // counted; walls are not touched.
  Config tight = config(true);
  tight.backend.graph.level_view_max_tilt_deg = 1e-6;
  const std::string out = file("out_tilt_tight");
  runPipeline(bag(), tight, out);
  std::ifstream report_file(std::filesystem::path(out) / "report.json");
  const nlohmann::json report = nlohmann::json::parse(report_file);
  const int tilted = report["backend"]["association"]["tilted_level_views"].get<int>();
  std::ifstream planes_file(std::filesystem::path(out) / "planes.json");
  const nlohmann::json planes = nlohmann::json::parse(planes_file);
  int level_views = 0, wall_views = 0, walls_flagged = 0;
  for (const auto& plane : planes["planes"]) {
    const bool level = std::abs(plane["normal"][2].get<double>()) > std::cos(5.0 * M_PI / 180.0);
    for (const auto& o : plane["observations"]) {
      if (level) {
        ++level_views;
        EXPECT_TRUE(o["outlier"].get<bool>());
      } else {
        ++wall_views;
        walls_flagged += o["outlier"].get<bool>();
      }
    }
  }
  EXPECT_GT(level_views, 5);
  EXPECT_EQ(tilted, level_views);
  EXPECT_GT(wall_views, 5);
  EXPECT_LT(walls_flagged, wall_views / 4);
}

TEST_F(BackendTiny, TrackedLandmarksKeepTheirFace) {
  // Tracking with a gate wider than the building changes nothing: the same
  // trajectory as without tracking (the default).
  const PipelineResult untracked = runPipeline(bag(), config(true), file("out_untracked"));
  Config wide = config(true);
  wide.backend.association.track_distance = 1000.0;
  wide.backend.association.track_gate = 100.0;
  const PipelineResult r_wide = runPipeline(bag(), wide, file("out_track_wide"));
  ASSERT_EQ(r_wide.trajectory.size(), untracked.trajectory.size());
  for (std::size_t i = 0; i < untracked.trajectory.size(); ++i) {
    ASSERT_EQ(r_wide.trajectory[i].pose.translation(), untracked.trajectory[i].pose.translation())
        << i;
  }
  // A gate no re-observation meets (0.1 mm: the fits' noise is millimetres):
  // the odometry-moved newest views turn candidates away, counted; every SRP
  // still has exactly one outcome.
  Config tight = config(true);
  tight.backend.association.track_distance = 1000.0;
  tight.backend.association.track_gate = 1e-4;
  const std::string out = file("out_track_tight");
  runPipeline(bag(), tight, out);
  std::ifstream in(std::filesystem::path(out) / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& association = report.at("backend").at("association");
  EXPECT_GT(association.at("rejected_pairs_by_gate").at("not_the_tracked_face").get<int>(), 10);
  int outcomes = 0;
  for (const auto& [name, count] : association.at("outcomes").items()) outcomes += count.get<int>();
  EXPECT_EQ(outcomes, report.at("backend").at("srps").get<int>());
  std::ifstream untracked_in(std::filesystem::path(file("out_untracked")) / "report.json");
  const nlohmann::json untracked_report = nlohmann::json::parse(untracked_in);
  EXPECT_EQ(untracked_report.at("backend")
                .at("association")
                .at("rejected_pairs_by_gate")
                .at("not_the_tracked_face")
                .get<int>(),
            0);
  EXPECT_GT(
      association.at("outcomes").at("new_plane").get<int>(),
      untracked_report.at("backend").at("association").at("outcomes").at("new_plane").get<int>());
}

TEST_F(BackendTiny, NoSrpKeepsTheOdometry) {
  const std::string out = file("out_nosrp");
  const PipelineResult r = runPipeline(bag(), config(false), out);
  ASSERT_EQ(r.trajectory.size(), r.odometry.size());
  for (std::size_t i = 0; i < r.trajectory.size(); ++i) {  // the same numbers
    ASSERT_EQ(r.trajectory[i].pose.translation(), r.odometry[i].pose.translation());
    ASSERT_EQ(r.trajectory[i].pose.rotation().coeffs(), r.odometry[i].pose.rotation().coeffs());
  }
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(out) / "planes.json"));
}

}  // namespace
}  // namespace storey
