// `storey batch` on a real Slurm cluster (single node, started and stopped by
// tests/e2e/with_slurm.sh around this program) and with the local executor:
// four tiny simulated logs, one of them corrupt. Three are mapped and the
// corrupt one fails with its error in fleet.json; a re-run skips the three; a
// changed config runs them again; --only-failed runs only the corrupt one;
// the local executor maps the same trajectories; --submit-only + --status.
// The tests run in order and share the logs and the fleet folder.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/run_storey.h"
#include "support/temp_dir.h"

namespace storey::test {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

class BatchSlurm : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    for (int seed = 1; seed <= 3; ++seed) {
      const RunResult sim =
          runStorey("simulate tiny --duration 8 --no-progress --seed " + std::to_string(seed) +
                        " -o " + logs("walk" + std::to_string(seed)),
                    dir_->path().string());
      ASSERT_EQ(sim.exit_code, 0) << sim.err;
      fs::remove(logs("walk" + std::to_string(seed) + "/building.ply"));
    }
    // The corrupt log: the first 300 kB of a bag (its index is missing).
    fs::create_directories(logs("broken"));
    const std::string bag = readText(logs("walk1/simulation.bag"));
    ASSERT_GT(bag.size(), 300000u);
    dir_->write("logs/broken/simulation.bag", bag.substr(0, 300000));
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::string logs(const std::string& name = "") { return dir_->file("logs/" + name); }
  static std::string file(const std::string& name) { return dir_->file(name); }
  static RunResult batch(const std::string& args) {
    return runStorey(
        "batch " + logs() + " --calibration " + logs("walk1/calibration.yaml") + " " + args,
        dir_->path().string());
  }
  static Json fleet(const std::string& out) {
    return Json::parse(readText(file(out + "/fleet.json")), nullptr, false);
  }
  static const Json& row(const Json& fleet, const std::string& name) {
    for (const Json& r : fleet["logs"])
      if (r["name"] == name) return r;
    static const Json none;
    ADD_FAILURE() << "no row " << name;
    return none;
  }
  static fs::file_time_type mtime(const std::string& path) { return fs::last_write_time(path); }

  static inline std::unique_ptr<TempDir> dir_;
};

const char* kWalks[] = {"walk1-simulation", "walk2-simulation", "walk3-simulation"};

TEST_F(BatchSlurm, ClusterIsUp) {
  // with_slurm.sh sets SLURM_CONF; without it this is not a Slurm test.
  ASSERT_NE(std::getenv("SLURM_CONF"), nullptr)
      << "run through tests/e2e/with_slurm.sh (ctest does)";
  EXPECT_EQ(std::system("sinfo -h >/dev/null"), 0);
}

TEST_F(BatchSlurm, ThreeMappedTheCorruptOneFailsWithItsError) {
  const RunResult r = batch("-o " + file("fleet") + " --executor slurm --jobs 2 --poll 1");
  EXPECT_EQ(r.exit_code, 1) << r.err;  // a log failed
  EXPECT_NE(r.err.find("4 to run, 4 new"), std::string::npos) << r.err;
  const std::string script = readText(file("fleet/state/slurm/submission-1.sh"));
  EXPECT_NE(script.find("#SBATCH --array=0-3%2"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --mem="), std::string::npos);
  const Json f = fleet("fleet");
  ASSERT_TRUE(f.is_object());
  EXPECT_EQ(f["totals"]["done"], 3);
  EXPECT_EQ(f["totals"]["failed"], 1);
  EXPECT_EQ(f["executor"], "slurm");
  for (const char* name : kWalks) {
    const Json& w = row(f, name);
    EXPECT_EQ(w["status"], "done");
    EXPECT_GT(w["log_duration_s"].get<double>(), 5.0);
    EXPECT_GT(w["path_length_m"].get<double>(), 1.0);
    EXPECT_TRUE(w["end_point_drift_m"].is_number());
    EXPECT_TRUE(w["storeys_found"].is_number());
    EXPECT_GT(w["map_points"].get<double>(), 1000.0);
    EXPECT_GT(w["wall_time_s"].get<double>(), 0.0);
    EXPECT_GT(w["peak_memory_mb"].get<double>(), 10.0);
    EXPECT_NE(w["executor"].get<std::string>().find("slurm job"), std::string::npos);
    EXPECT_TRUE(fs::exists(file("fleet/" + w["thumbnail"].get<std::string>())));
    EXPECT_TRUE(fs::exists(file("fleet/logs/" + std::string(name) + "/trajectory.tum")));
  }
  const Json& broken = row(f, "broken-simulation");
  EXPECT_EQ(broken["status"], "failed");
  EXPECT_EQ(broken["attempts"], 2);  // --retries 1 by default
  const std::string error = broken["error"];
  EXPECT_NE(error.find(logs("broken/simulation.bag")), std::string::npos) << error;
  EXPECT_NE(error.find("truncated or damaged ROS bag"), std::string::npos) << error;
  EXPECT_EQ(f["failures"][0]["error"], error);
  EXPECT_FALSE(fs::exists(file("fleet/logs/broken-simulation")));
  EXPECT_NE(readText(file("fleet/fleet.html")).find("truncated or damaged ROS bag"),
            std::string::npos);
}

TEST_F(BatchSlurm, ReRunSkipsTheFinishedLogs) {
  const auto before = mtime(file("fleet/logs/walk1-simulation/trajectory.tum"));
  const RunResult r = batch("-o " + file("fleet") + " --executor slurm --jobs 2 --poll 1");
  EXPECT_EQ(r.exit_code, 1) << r.err;  // the failed log is still reported
  EXPECT_NE(r.err.find("0 to run; 4 skipped"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(file("fleet/state/slurm/submission-2.sh")));  // nothing submitted
  EXPECT_EQ(mtime(file("fleet/logs/walk1-simulation/trajectory.tum")), before);
  const Json f = fleet("fleet");
  EXPECT_EQ(f["totals"]["done"], 3);
  for (const Json& r2 : f["logs"]) EXPECT_EQ(r2["this_batch"], "skipped");
}

TEST_F(BatchSlurm, AChangedConfigRunsThemAgain) {
  dir_->write("coarse.yaml", "map:\n  voxel_size: 0.05\n");
  const Json old = fleet("fleet");
  const RunResult r =
      batch("-o " + file("fleet") + " -c " + file("coarse.yaml") + " --executor slurm --poll 1");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("4 to run, 4 config changed"), std::string::npos) << r.err;
  const Json f = fleet("fleet");
  EXPECT_EQ(f["totals"]["done"], 3);
  for (const char* name : kWalks) {
    EXPECT_EQ(row(f, name)["this_batch"], "run: config changed");
    EXPECT_LT(row(f, name)["map_points"].get<double>(), row(old, name)["map_points"].get<double>());
  }
  EXPECT_NE(readText(file("fleet/state/walk1-simulation/config.yaml")).find("voxel_size: 0.05"),
            std::string::npos);
}

TEST_F(BatchSlurm, OnlyFailedRunsTheFailedLog) {
  const RunResult r = batch("-o " + file("fleet") + " -c " + file("coarse.yaml") +
                            " --executor slurm --poll 1 --only-failed --retries 0");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("1 to run, 1 failed before"), std::string::npos) << r.err;
  const Json f = fleet("fleet");
  EXPECT_EQ(row(f, "broken-simulation")["attempts"], 1);
  EXPECT_EQ(row(f, "walk1-simulation")["this_batch"], "skipped");
}

TEST_F(BatchSlurm, TheLocalExecutorGivesTheSameResults) {
  const RunResult r =
      batch("-o " + file("local") + " -c " + file("coarse.yaml") + " --executor local --jobs 2");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const Json local = fleet("local"), slurm = fleet("fleet");
  EXPECT_EQ(local["totals"]["done"], 3);
  EXPECT_EQ(local["totals"]["failed"], 1);
  EXPECT_EQ(row(local, "broken-simulation")["error"], row(slurm, "broken-simulation")["error"]);
  for (const char* name : kWalks) {
    for (const char* out : {"trajectory.tum", "keyframes.tum", "storeys.json"}) {
      const std::string a = readText(file("local/logs/" + std::string(name) + "/" + out));
      EXPECT_FALSE(a.empty());
      EXPECT_EQ(a, readText(file("fleet/logs/" + std::string(name) + "/" + out)))
          << name << "/" << out << " differs between the executors";
    }
    EXPECT_EQ(row(local, name)["map_points"], row(slurm, name)["map_points"]);
  }
}

TEST_F(BatchSlurm, SubmitOnlyThenStatus) {
  const RunResult r = runStorey("batch " + logs("walk1/simulation.bag") + " --calibration " +
                                    logs("walk1/calibration.yaml") + " -o " + file("later") +
                                    " --executor slurm --submit-only",
                                dir_->path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("storey batch --status " + file("later")), std::string::npos) << r.out;
  EXPECT_NE(readText(file("later/state/slurm/collect-1.sh")).find("--dependency=afterany:"),
            std::string::npos);
  EXPECT_EQ(fleet("later")["totals"]["queued"], 1);
  // The collect job rewrites fleet.json once the array has ended.
  Json f;
  for (int i = 0; i < 600; ++i) {
    f = fleet("later");
    if (f.is_object() && f["totals"]["done"] == 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  EXPECT_EQ(f["totals"]["done"], 1) << f.dump(1);
  const RunResult status = runStorey("batch --status " + file("later"), dir_->path().string());
  EXPECT_EQ(status.exit_code, 0) << status.err;
  EXPECT_NE(status.out.find("1 done, 0 failed"), std::string::npos) << status.out;
}

}  // namespace
}  // namespace storey::test
