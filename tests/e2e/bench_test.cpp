// `storey bench`: the table's arithmetic (storey-height errors from floor
// errors, distributions) on hand-made values, and one short seed end to end.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench_table.h"
#include "support/run_storey.h"
#include "support/temp_dir.h"

namespace storey::cli {
namespace {

TEST(BenchTable, StoreyHeightErrorsFromConsecutiveFloors) {
  // Floors 0..3 off by +0.01, +0.04, -0.01 and (missed) storey 3: heights off by
  // 0.03 (0->1) and 0.05 (1->2); storey 4 follows a missed one: not a height.
  EXPECT_NEAR(*worstStoreyHeightError({{2, -0.01}, {0, 0.01}, {1, 0.04}, {4, 0.2}}), 0.05, 1e-12);
  EXPECT_FALSE(worstStoreyHeightError({{0, 0.01}}));
  EXPECT_FALSE(worstStoreyHeightError({{0, 0.01}, {2, 0.3}}));
}

TEST(BenchTable, DistributionsLeaveOutMissingValues) {
  std::vector<std::optional<double>> v;
  for (int i = 1; i <= 10; ++i) v.push_back(i);
  v.push_back(std::nullopt);
  const Distribution d = distributionOf(v);
  EXPECT_EQ(d.count, 10u);
  EXPECT_EQ(d.median, 5.0);  // nearest rank
  EXPECT_EQ(d.p90, 9.0);
  EXPECT_EQ(d.worst, 10.0);
  const Distribution higher = distributionOf(v, true);
  EXPECT_EQ(higher.worst, 1.0);
  EXPECT_EQ(higher.p90, 1.0);  // the 10th percentile
  EXPECT_EQ(distributionOf({}).count, 0u);
}

TEST(BenchTable, AFailedSeedIsARowWithItsError) {
  BenchRow ok, failed;
  ok.seed = 1;
  ok.ate_m = 0.02;
  ok.lidar = "VLP-16";
  failed.seed = 2;
  failed.error = "run: storey: error: something went wrong";
  const std::string md = benchMarkdown({ok, failed}, "t");
  EXPECT_NE(md.find("| 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("**failed:** run: storey: error: something went wrong"), std::string::npos);
  EXPECT_NE(md.find("Failed seeds: 1 of 2"), std::string::npos);
  EXPECT_NE(md.find("| ATE m | 0.020 | 0.020 | 0.020 | 1 |"), std::string::npos) << md;
  const nlohmann::json j = nlohmann::json::parse(benchJson({ok, failed}));
  EXPECT_EQ(j["seeds"][1]["error"], "run: storey: error: something went wrong");
  EXPECT_EQ(j["distribution"]["ATE m"]["count"], 1);
}

TEST(BenchCli, OneShortSeedEndToEnd) {
  test::TempDir dir;
  const std::string out = (dir.path() / "bench").string();
  const test::RunResult run = test::runStorey(
      "bench --seeds 18 --jobs 1 --duration 12 -o " + test::shellQuoted(out), dir.path().string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("[1/1] seed 18"), std::string::npos) << run.err;
  std::ifstream in(out + "/benchmark.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["seeds"].size(), 1u);
  const nlohmann::json& row = j["seeds"][0];
  EXPECT_TRUE(row["error"].is_null()) << row.dump();
  EXPECT_EQ(row["storeys"], 2);
  EXPECT_LT(row["ATE m"].get<double>(), 0.1);
  EXPECT_LT(row["odometry ATE m"].get<double>(), 0.2) << "the front end alone, evaluated too";
  EXPECT_TRUE(row["wrong matches"].is_number()) << "the plane associations, checked";
  EXPECT_GT(row["peak MB"].get<double>(), 10.0);
  EXPECT_GT(row["RT factor"].get<double>(), 0.0);
  EXPECT_TRUE(std::filesystem::exists(out + "/benchmark.md"));
  EXPECT_TRUE(std::filesystem::exists(out + "/seed-18/sim/spec.yaml"));
  EXPECT_FALSE(std::filesystem::exists(out + "/seed-18/sim/simulation.bag")) << "not --keep";

  // --resume keeps the finished seed: nothing simulated again, the same row.
  const auto spec_time = std::filesystem::last_write_time(out + "/seed-18/sim/spec.yaml");
  const test::RunResult resumed = test::runStorey(
      "bench --seeds 18 --jobs 1 --duration 12 --resume -o " + test::shellQuoted(out),
      dir.path().string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("seed 18: 2 storeys"), std::string::npos) << resumed.err;
  EXPECT_NE(resumed.err.find("(kept from an earlier run)"), std::string::npos) << resumed.err;
  EXPECT_EQ(std::filesystem::last_write_time(out + "/seed-18/sim/spec.yaml"), spec_time);
  std::ifstream again(out + "/benchmark.json");
  EXPECT_EQ(nlohmann::json::parse(again)["seeds"][0], row);

  // -c: every seed mapped with that configuration; --resume does not keep a
  // seed that ran with another one.
  const std::string config = (dir.path() / "window.yaml").string();
  {
    std::ofstream file(config);
    file << "backend:\n  graph:\n    window_keyframes: 10\n";
  }
  const test::RunResult configured =
      test::runStorey("bench --seeds 18 --jobs 1 --duration 12 --resume -o " +
                          test::shellQuoted(out) + " -c " + test::shellQuoted(config),
                      dir.path().string());
  ASSERT_EQ(configured.exit_code, 0) << configured.err;
  EXPECT_EQ(configured.err.find("(kept from an earlier run)"), std::string::npos) << configured.err;
  std::ifstream md(out + "/benchmark.md");
  const std::string table((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(table.find(" -c " + config), std::string::npos) << table;
  std::ifstream record(out + "/seed-18/seed.json");
  EXPECT_EQ(nlohmann::json::parse(record)["config"],
            "backend:\n  graph:\n    window_keyframes: 10\n");
}

TEST(BenchCli, RetryFailedRunsAFailedSeedAgain) {
  test::TempDir dir;
  const std::string out = (dir.path() / "bench").string();
  std::filesystem::create_directories(out + "/seed-18");
  BenchRow failed;
  failed.seed = 18;
  failed.error = "run: storey: error: disk full?";
  {
    std::ofstream record(out + "/seed-18/seed.json");
    record << seedRecordJson(failed, 12.0, "");
  }
  const std::string command =
      "bench --seeds 18 --jobs 1 --duration 12 --resume -o " + test::shellQuoted(out);
  // --resume alone keeps the failed row: nothing runs.
  const test::RunResult kept = test::runStorey(command, dir.path().string());
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_NE(kept.err.find("seed 18: FAILED (run: storey: error: disk full?) (kept"),
            std::string::npos)
      << kept.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/seed-18/sim")) << "nothing simulated";
  // --retry-failed runs it again; the new row replaces the failed one.
  const test::RunResult retried = test::runStorey(command + " --retry-failed", dir.path().string());
  ASSERT_EQ(retried.exit_code, 0) << retried.err;
  EXPECT_EQ(retried.err.find("(kept from an earlier run)"), std::string::npos) << retried.err;
  EXPECT_NE(retried.err.find("seed 18: 2 storeys"), std::string::npos) << retried.err;
  std::ifstream in(out + "/benchmark.json");
  const nlohmann::json row = nlohmann::json::parse(in)["seeds"][0];
  EXPECT_TRUE(row["error"].is_null()) << row.dump();
  // Without --resume the flag is refused (CLI11: --retry-failed needs --resume).
  const test::RunResult alone = test::runStorey(
      "bench --seeds 18 --retry-failed -o " + test::shellQuoted(out), dir.path().string());
  EXPECT_NE(alone.exit_code, 0);
}

TEST(BenchTable, ASeedRecordIsKeptOnlyForItsSeedAndDuration) {
  test::TempDir dir;
  BenchRow row;
  row.seed = 7;
  row.peak_memory_mb = 321.0;
  row.error = "run: storey: error: it broke";
  {
    std::ofstream out(dir.path() / "seed.json");
    out << seedRecordJson(row, 12.0, "");
  }
  BenchRow kept;
  EXPECT_FALSE(readSeedRecord(dir.path().string(), 8, 12.0, "", kept)) << "another seed's record";
  EXPECT_FALSE(readSeedRecord(dir.path().string(), 7, 0.0, "", kept)) << "another --duration";
  EXPECT_FALSE(readSeedRecord(dir.path().string(), 7, 12.0, "a: 1\n", kept))
      << "another configuration";
  EXPECT_EQ(kept.seed, 0u) << "a record not kept leaves the row alone";
  ASSERT_TRUE(readSeedRecord(dir.path().string(), 7, 12.0, "", kept));
  EXPECT_EQ(kept.seed, 7u);
  EXPECT_EQ(kept.error, "run: storey: error: it broke");
  EXPECT_EQ(kept.peak_memory_mb, 321.0);
  {
    std::ofstream out(dir.path() / "seed.json");
    out << "{\"format\": \"storey-bench-seed\", \"seed\": 7";  // cut short
  }
  EXPECT_FALSE(readSeedRecord(dir.path().string(), 7, 12.0, "", kept));
  {
    std::ofstream out(dir.path() / "seed.json");
    out << seedRecordJson(row, 12.0, "a: 1\n");
  }
  EXPECT_FALSE(readSeedRecord(dir.path().string(), 7, 12.0, "", kept)) << "run with -c";
  EXPECT_TRUE(readSeedRecord(dir.path().string(), 7, 12.0, "a: 1\n", kept));
  {
    // A record from before -c existed: the defaults.
    std::ofstream out(dir.path() / "seed.json");
    out << R"({"format": "storey-bench-seed", "version": 1, "seed": 7, "max_duration_s": 12.0,
              "error": null, "peak_memory_mb": 5.0})";
  }
  EXPECT_TRUE(readSeedRecord(dir.path().string(), 7, 12.0, "", kept));
  EXPECT_FALSE(readSeedRecord(dir.path().string(), 7, 12.0, "a: 1\n", kept));
}

TEST(BenchCli, AWrongConfigurationFailsBeforeAnythingRuns) {
  test::TempDir dir;
  const std::string out = (dir.path() / "bench").string();
  const std::string config = (dir.path() / "bad.yaml").string();
  {
    std::ofstream file(config);
    file << "backend:\n  graph:\n    windw_keyframes: 20\n";
  }
  const test::RunResult run = test::runStorey(
      "bench --seeds 18 -o " + test::shellQuoted(out) + " -c " + test::shellQuoted(config),
      dir.path().string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("unknown key 'backend.graph.windw_keyframes'"), std::string::npos)
      << run.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << "nothing written";
}

/// Processes whose command line mentions `text` (from /proc).
int processesMentioning(const std::string& text) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (cmdline.find(text) != std::string::npos) ++count;
  }
  return count;
}

TEST(BenchCli, StoppingTheBenchStopsItsSteps) {
  test::TempDir dir;
  const std::string out = (dir.path() / "stopped_bench").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execl(STOREY_BINARY, STOREY_BINARY, "bench", "--seeds", "1", "--jobs", "1", "-o", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until its first step (the simulation of seed 1, minutes long) runs.
  for (int i = 0; i < 100 && processesMentioning(out + "/seed-1/sim") == 0; ++i) usleep(100000);
  ASSERT_GT(processesMentioning(out + "/seed-1/sim"), 0) << "the bench did not start its step";
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  int left = 1;
  for (int i = 0; i < 50 && (left = processesMentioning(out)) > 0; ++i) usleep(100000);
  EXPECT_EQ(left, 0) << "steps outlived the bench";
}

}  // namespace
}  // namespace storey::cli
