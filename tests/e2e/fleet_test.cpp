// `storey batch` parts without a cluster: which logs and their names
// (folders, manifests), the skip decisions, the Slurm resource estimates, the
// fleet report from hand-made states; and the local executor stopped by SIGINT.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "common/error.h"
#include "executor_slurm.h"
#include "fleet_inputs.h"
#include "fleet_report.h"
#include "fleet_state.h"
#include "support/run_storey.h"
#include "support/temp_dir.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using test::TempDir;

TEST(FleetInputs, NamesTakeParentFoldersOnlyWhenNeeded) {
  EXPECT_EQ(uniqueLogNames({"/d/a/simulation.bag", "/d/b/simulation.bag", "/d/c/other.pcap"}),
            (std::vector<std::string>{"a-simulation", "b-simulation", "other"}));
  EXPECT_EQ(uniqueLogNames({"/x/site 1/run.bag"}), (std::vector<std::string>{"run"}));
  EXPECT_EQ(uniqueLogNames({"/x/site 1/run.bag", "/x/site 2/run.bag"}),
            (std::vector<std::string>{"site_1-run", "site_2-run"}));
  // A given name is kept; the other log keeps its short name.
  EXPECT_EQ(uniqueLogNames({"/a/run.bag", "/b/run.bag"}, {"first", ""}),
            (std::vector<std::string>{"first", "run"}));
}

TEST(FleetInputs, FolderSearchAndManifest) {
  TempDir dir;
  fs::create_directories(dir.path() / "site/a");
  fs::create_directories(dir.path() / "site/b/scans");
  dir.write("site/a/walk.bag", "x");
  dir.write("site/a/notes.txt", "x");
  dir.write("site/b/scans/0001.pcd", "x");  // a PCD folder is one log
  dir.write("site/b/capture.PCAP", "x");
  fs::create_directories(dir.path() / "site/c/ros2walk");  // a rosbag2 folder is one log
  dir.write("site/c/ros2walk/metadata.yaml", "x");
  dir.write("site/c/ros2walk/ros2walk_0.db3", "x");
  dir.write("site/c/outdoor.mcap", "x");
  dir.write("calib.yaml", "x");
  const FleetInputs found = collectFleetInputs({dir.file("site")}, "");
  ASSERT_EQ(found.logs.size(), 5u);
  EXPECT_EQ(found.logs[0].name, "walk");
  EXPECT_EQ(found.logs[1].name, "capture");
  EXPECT_EQ(found.logs[2].name, "scans");
  EXPECT_EQ(found.logs[3].name, "outdoor");
  EXPECT_EQ(found.logs[4].name, "ros2walk");
  EXPECT_TRUE(found.logs[2].calibration.empty());
  // A rosbag2 folder given itself is that log, not a folder to search.
  const FleetInputs one = collectFleetInputs({dir.file("site/c/ros2walk")}, "");
  ASSERT_EQ(one.logs.size(), 1u);
  EXPECT_EQ(one.logs[0].name, "ros2walk");

  dir.write("fleet.yaml", R"(config: base.yaml
slurm: {partition: short, mem: 8G, extra_args: ["--qos=low"]}
logs:
  - site/a/walk.bag
  - path: site/b/capture.PCAP
    name: cap-1
    calibration: calib.yaml
    config: {map: {voxel_size: 0.05}}
)");
  const FleetInputs manifest = collectFleetInputs({dir.file("fleet.yaml")}, "");
  ASSERT_EQ(manifest.logs.size(), 2u);
  EXPECT_EQ(manifest.config_path, dir.file("base.yaml"));
  EXPECT_EQ(manifest.slurm.partition, "short");
  EXPECT_EQ(manifest.slurm.mem, "8G");
  EXPECT_EQ(manifest.slurm.extra_args, std::vector<std::string>{"--qos=low"});
  EXPECT_EQ(manifest.logs[0].path, dir.file("site/a/walk.bag"));
  EXPECT_EQ(manifest.logs[1].name, "cap-1");
  EXPECT_EQ(manifest.logs[1].calibration, dir.file("calib.yaml"));
  EXPECT_NE(manifest.logs[1].config_overrides.find("voxel_size"), std::string::npos);

  dir.write("typo.yaml", "logs:\n  - path: site/a/walk.bag\n    calibraton: calib.yaml\n");
  try {
    collectFleetInputs({dir.file("typo.yaml")}, "");
    FAIL() << "a mistyped key must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'logs[0].calibraton' (line 3)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(collectFleetInputs({dir.file("site/a/walk.bag"), dir.file("site")}, ""), Error);
  EXPECT_THROW(collectFleetInputs({dir.file("missing.bag")}, ""), Error);
  fs::create_directories(dir.path() / "empty");
  EXPECT_THROW(collectFleetInputs({dir.file("empty")}, ""), Error);
}

TEST(FleetState, RunsWhatChangedOrNeverFinished) {
  TempDir dir;
  FleetLog log;
  log.path = dir.write("a.bag", "first");
  const Json used = usedBy(log, "map: {voxel_size: 0.02}");
  EXPECT_EQ(whyRun(std::nullopt, used, false, false), "new");
  LogState done;
  done.status = "done";
  done.used = used;
  EXPECT_EQ(whyRun(done, used, false, false), "");
  EXPECT_EQ(whyRun(done, used, false, true), "--force");
  EXPECT_EQ(whyRun(done, used, true, false), "");
  EXPECT_EQ(whyRun(done, usedBy(log, "map: {voxel_size: 0.03}"), false, false), "config changed");
  dir.write("a.bag", "second, longer");
  EXPECT_EQ(whyRun(done, usedBy(log, "map: {voxel_size: 0.02}"), false, false), "input changed");
  Json other_version = used;
  other_version["storey_version"] = "0.0.9";
  done.used = other_version;
  EXPECT_EQ(whyRun(done, used, false, false), "Storey version changed");
  LogState failed = done;
  failed.status = "failed";
  failed.used = used;
  EXPECT_EQ(whyRun(failed, used, false, false), "");  // failed after its retries: reported
  EXPECT_EQ(whyRun(failed, used, true, false), "failed before");
  LogState running = failed;
  running.status = "running";  // interrupted
  EXPECT_EQ(whyRun(running, used, false, false), "not finished (running)");

  const std::string path = dir.file("state/a/state.json");
  failed.error = "a.bag: damaged";
  failed.attempts = 2;
  writeLogState(path, failed);
  const auto back = readLogState(path);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->status, "failed");
  EXPECT_EQ(back->error, "a.bag: damaged");
  EXPECT_EQ(back->attempts, 2);
  EXPECT_EQ(back->used, used);
}

TEST(FleetReport, RowsTotalsAndFailuresFromStates) {
  TempDir dir;
  FleetPlan plan;
  plan.fleet_out = dir.path().string();
  plan.executor = "local";
  const FleetPaths paths{plan.fleet_out};
  for (const char* name : {"good", "bad"}) {
    PlannedLog p;
    p.log.name = name;
    p.log.path = std::string("/logs/") + name + ".bag";
    p.reason = "new";
    plan.tasks.push_back(plan.logs.size());
    plan.logs.push_back(p);
  }
  LogState good;
  good.status = "done";
  good.submission = 1;
  good.wall_time_s = 12.5;
  good.peak_memory_mb = 300;
  writeLogState(paths.stateFile("good"), good);
  fs::create_directories(paths.logOut("good") + "/renders");
  std::ofstream(paths.logOut("good") + "/renders/elevation_front.png") << "png";
  std::ofstream(paths.logOut("good") + "/report.json")
      << R"({"log_duration_s": 24.7, "end_point_drift": {"path_length_m": 9.5, "dXYZ_m": 0.001},
            "storeys": [{"index": 0}], "map": {"points": 257103}})";
  LogState bad = good;
  bad.status = "failed";
  bad.error = "/logs/bad.bag: truncated";
  bad.attempts = 2;
  writeLogState(paths.stateFile("bad"), bad);

  const Json fleet = writeFleetReport(plan);
  EXPECT_EQ(fleet["totals"]["done"], 1);
  EXPECT_EQ(fleet["totals"]["failed"], 1);
  EXPECT_DOUBLE_EQ(fleet["totals"]["path_length_m"].get<double>(), 9.5);
  const Json& row = fleet["logs"][0];
  EXPECT_DOUBLE_EQ(row["log_duration_s"].get<double>(), 24.7);
  EXPECT_DOUBLE_EQ(row["end_point_drift_m"].get<double>(), 0.001);
  EXPECT_EQ(row["storeys_found"], 1);
  EXPECT_EQ(row["map_points"], 257103);
  EXPECT_DOUBLE_EQ(row["peak_memory_mb"].get<double>(), 300.0);
  EXPECT_EQ(row["thumbnail"], "logs/good/renders/elevation_front.png");
  EXPECT_EQ(fleet["failures"][0]["error"], "/logs/bad.bag: truncated");
  const std::string html = test::readText(dir.file("fleet.html"));
  EXPECT_NE(html.find("<a href=\"logs/good/report.html\"><img src=\"logs/good/renders/"
                      "elevation_front.png\""),
            std::string::npos);
  EXPECT_NE(html.find("/logs/bad.bag: truncated"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos);  // nothing fetched from the network
}

TEST(SlurmResources, EstimatesGrowWithTheLog) {
  EXPECT_GE(estimateMemoryMb(124'000'000, 25.0), 1024.0);
  EXPECT_GT(estimateMemoryMb(20'000'000'000, 7200.0), estimateMemoryMb(1'000'000'000, 300.0));
  // Measured peaks (docs/batch.md) stay under the estimate.
  EXPECT_GT(estimateMemoryMb(1'717'750'045, 295.3), 843.0);
  EXPECT_GT(estimateMemoryMb(6'309'275'317, 1073.0), 1.5 * 1228.0);
  EXPECT_GT(estimateTimeSeconds(3600.0), 3600.0);
  EXPECT_NEAR(logDurationSeconds("/nonexistent", 50'000'000), 10.0, 1e-9);
}

/// SIGINT while the local executor maps: children stopped, no half-written
/// output folder, the log "cancelled" and run again by the next batch.
TEST(LocalExecutor, CtrlCStopsCleanly) {
  TempDir dir;
  const std::string sim = dir.file("sim");
  ASSERT_EQ(test::runStorey("simulate tiny --duration 12 --no-progress -o " + sim, dir.file("."))
                .exit_code,
            0);
  const std::string fleet = dir.file("fleet");
  const std::string command = std::string(STOREY_BINARY) + " batch " + sim +
                              "/simulation.bag --calibration " + sim + "/calibration.yaml -o " +
                              fleet + " > " + dir.file("out.txt") + " 2>&1";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until its `storey run` has started (state "running"), then Ctrl-C.
  const std::string state = fleet + "/state/simulation/state.json";
  for (int i = 0; i < 600 && test::readText(state).find("\"running\"") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_NE(test::readText(state).find("\"running\""), std::string::npos);
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1) << test::readText(dir.file("out.txt"));
  EXPECT_NE(test::readText(dir.file("out.txt")).find("stopped"), std::string::npos);
  EXPECT_NE(test::readText(state).find("\"cancelled\""), std::string::npos);
  for (const auto& e : fs::directory_iterator(fleet + "/logs"))
    ADD_FAILURE() << "left behind: " << e.path();
  const Json report = Json::parse(test::readText(fleet + "/fleet.json"));
  EXPECT_EQ(report["totals"]["cancelled"], 1);
  // The next batch maps it.
  const auto again = test::runStorey(
      "batch " + sim + "/simulation.bag --calibration " + sim + "/calibration.yaml -o " + fleet,
      dir.file("."));
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("1 not finished (cancelled)"), std::string::npos) << again.err;
  EXPECT_TRUE(fs::exists(fleet + "/logs/simulation/trajectory.tum"));
}

}  // namespace
}  // namespace storey::cli
