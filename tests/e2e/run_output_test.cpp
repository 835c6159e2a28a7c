// `storey run --preset tiny` as a person (or a CI log) sees it: with stderr
// not a terminal, plain progress lines and log lines, never a bar; on stdout
// the summary, whose numbers are the run report's.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_storey.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// The value of the summary line labelled `label` ("" when there is none).
std::string summaryValue(const std::string& out, const std::string& label) {
  for (const std::string& line : lines(out)) {
    const std::regex pattern("^  " + label + "  +(.*)$");
    std::smatch m;
    if (std::regex_match(line, m, pattern)) return m[1];
  }
  return "";
}

class RunOutput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    run_ = new test::RunResult(test::runStorey(
        "run --preset tiny --no-render -o " + test::shellQuoted(out()), dir_->path().string()));
  }
  static void TearDownTestSuite() {
    delete run_;
    delete dir_;
  }
  static std::string out() { return dir_->file("out"); }
  static test::TempDir* dir_;
  static test::RunResult* run_;
};
test::TempDir* RunOutput::dir_ = nullptr;
test::RunResult* RunOutput::run_ = nullptr;

TEST_F(RunOutput, StderrHasPlainProgressLinesAndLogLinesWhenItIsNoTerminal) {
  ASSERT_EQ(run_->exit_code, 0) << run_->err;
  EXPECT_EQ(run_->err.find('\r'), std::string::npos) << "no bar redrawn in place in a log file";
  EXPECT_EQ(run_->err.find("\033["), std::string::npos) << "no terminal escapes";
  const std::regex progress(
      R"(^storey run: (.+) (\d{1,3})% \((\d+:\d\d) elapsed, (\d+:\d\d|\?) left(, (\d+\.\d)x real time)?\)$)");
  std::size_t progress_lines = 0, odometry_lines = 0, with_time_left = 0;
  std::set<std::string> stages;
  for (const std::string& line : lines(run_->err)) {
    std::smatch m;
    if (std::regex_match(line, m, progress)) {
      ++progress_lines;
      stages.insert(m[1]);
      if (m[1] == "odometry") ++odometry_lines;
      if (m[4] != "?") ++with_time_left;
      if (m[5].matched) {
        EXPECT_EQ(m[1], "odometry") << "only the stage reading the log has a speed: " << line;
        EXPECT_GT(std::stod(m[6]), 0.0) << line;
      }
      continue;
    }
    // Everything else: a log message on its own line, or the run's own notes.
    EXPECT_TRUE(line.rfind("[info] ", 0) == 0 || line.rfind("[warning] ", 0) == 0 ||
                line.rfind("storey run: no LOG given", 0) == 0 ||
                line.rfind("storey run: simulated ", 0) == 0)
        << "unexpected stderr line: '" << line << "'";
  }
  for (const char* stage : {"ray-casting scans", "odometry", "map", "export", "writing outputs"})
    EXPECT_EQ(stages.count(stage), 1u) << stage << "\n" << run_->err;
  // One line per 10 % step of the odometry, not one per update (thousands).
  EXPECT_GE(odometry_lines, 5u) << run_->err;
  EXPECT_LE(odometry_lines, 13u) << run_->err;
  EXPECT_LT(progress_lines, 120u) << run_->err;
  EXPECT_GE(with_time_left, 1u) << run_->err;
  // (A speed needs 1 s of reading: the tiny log may be read faster than that.)
}

TEST_F(RunOutput, ReportHasThePeakMemoryAtTheEndOfEachStage) {
  ASSERT_EQ(run_->exit_code, 0) << run_->err;
  const nlohmann::json report =
      nlohmann::json::parse(test::readText(dir_->file("out/report.json")));
  const nlohmann::json& peak = report["peak_memory_mib_after"];
  double previous = 1.0;  // MiB: any real process holds more
  for (const char* stage : {"streaming", "map_build", "storeys", "export"}) {
    ASSERT_TRUE(peak.contains(stage)) << peak.dump();
    const double mib = peak[stage].get<double>();
    EXPECT_GE(mib, previous) << stage << ": a peak only grows; " << peak.dump();
    EXPECT_LT(mib, 4096.0) << stage;
    previous = mib;
  }
}

TEST_F(RunOutput, SummaryOnStdoutHasTheReportsNumbersAndTheFiles) {
  ASSERT_EQ(run_->exit_code, 0) << run_->err;
  const nlohmann::json report =
      nlohmann::json::parse(test::readText(dir_->file("out/report.json")));
  const std::string& o = run_->out;
  EXPECT_NE(o.find("storey run: finished\n"), std::string::npos) << o;
  EXPECT_EQ(summaryValue(o, "log"), out() + "/simulation/simulation.bag") << o;
  char expected[160];
  std::snprintf(expected, sizeof(expected), "%.1f s of log, %d scans",
                report["log_duration_s"].get<double>(), report["odometry"]["scans"].get<int>());
  EXPECT_EQ(summaryValue(o, "duration"), expected) << o;
  std::snprintf(expected, sizeof(expected), "%.3f m (%.2f %% of the path)",
                report["end_point_drift"]["dXYZ_m"].get<double>(),
                report["end_point_drift"]["dXYZ_percent_of_path"].get<double>());
  EXPECT_EQ(summaryValue(o, "end-point drift"), expected) << o;

  // The storeys with their floor elevations, bottom up.
  const nlohmann::json& storeys = report["storeys"];
  ASSERT_GE(storeys.size(), 1u) << "the tiny building has one storey";
  EXPECT_EQ(summaryValue(o, "storeys"), std::to_string(storeys.size()) + " found") << o;
  for (const nlohmann::json& s : storeys) {
    std::snprintf(expected, sizeof(expected), "floor at %.2f m",
                  s["floor_elevation"].get<double>());
    const std::string line = summaryValue(o, "  storey " + std::to_string(s["index"].get<int>()));
    EXPECT_EQ(line.rfind(expected, 0), 0u) << line << "\n" << o;
  }
  EXPECT_EQ(summaryValue(o, "map"),
            std::to_string(report["map"]["points"].get<std::size_t>()) + " points, voxel 0.02 m")
      << o;
  std::snprintf(expected, sizeof(expected), "%.1fx real time",
                report["real_time_factor"].get<double>());
  EXPECT_NE(summaryValue(o, "wall time").find(expected), std::string::npos) << o;
  EXPECT_EQ(summaryValue(o, "warnings"),
            report["warning_count"] == 0
                ? std::string("none")
                : std::to_string(report["warning_count"].get<int>()) + " (report.md)")
      << o;

  // The paths given exist.
  const std::string html = summaryValue(o, "report");
  EXPECT_EQ(html, out() + "/report.html");
  EXPECT_TRUE(fs::exists(html)) << "written by the run even with --no-render";
  EXPECT_EQ(summaryValue(o, "map files"), out() + "/map.las, map.ply, map.pcd") << o;
  for (const char* f : {"map.las", "map.ply", "map.pcd"}) EXPECT_TRUE(fs::exists(out() + "/" + f));
  EXPECT_TRUE(fs::exists(summaryValue(o, "trajectory")));
  // Aligned: every value starts in the same column.
  std::size_t column = std::string::npos;
  for (const std::string& line : lines(o)) {
    if (line.rfind("  ", 0) != 0) continue;
    const std::size_t gap = line.find("  ", line.find_first_not_of(' '));
    const std::size_t value = line.find_first_not_of(' ', gap);
    if (column == std::string::npos) column = value;
    EXPECT_EQ(value, column) << line;
  }
}

// `storey storeys` on the finished run: with the same settings the same
// files, byte for byte; another storeys: section changes the split; a map
// that does not belong to the keyframes, or the run folder as the output, is
// one line and exit 1 with nothing written.
TEST_F(RunOutput, StoreysSplitsTheRunsMapAgain) {
  ASSERT_EQ(run_->exit_code, 0) << run_->err;
  const std::string scratch = dir_->path().string();
  const std::string again = dir_->file("again");
  const test::RunResult same = test::runStorey(
      "storeys " + test::shellQuoted(out()) + " -o " + test::shellQuoted(again), scratch);
  ASSERT_EQ(same.exit_code, 0) << same.err;
  for (const char* f : {"storeys.json", "map.ply", "map.las", "map.pcd", "storeys/storey_00.las",
                        "storeys/storey_00.ply"})
    EXPECT_EQ(test::readText(again + "/" + f), test::readText(out() + "/" + f)) << f;
  EXPECT_NE(same.out.find("1 storeys in "), std::string::npos) << same.out;

  // Floors must be larger than the building: no storey.
  const std::string config =
      dir_->write("huge_floors.yaml", "storeys:\n  min_floor_area: 100000\n");
  const std::string none = dir_->file("none");
  const test::RunResult other = test::runStorey(
      "storeys " + test::shellQuoted(out()) + " -o " + test::shellQuoted(none) + " -c " + config,
      scratch);
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_NE(other.out.find("0 storeys in "), std::string::npos) << other.out;
  const nlohmann::json table = nlohmann::json::parse(test::readText(none + "/storeys.json"));
  EXPECT_TRUE(table["storeys"].empty()) << table.dump();

  const test::RunResult in_place = test::runStorey(
      "storeys " + test::shellQuoted(out()) + " -o " + test::shellQuoted(out()), scratch);
  EXPECT_EQ(in_place.exit_code, 1);
  EXPECT_NE(in_place.err.find("the run folder itself"), std::string::npos) << in_place.err;

  // keyframes.tum of a shorter walk: the map's keyframe labels point past it.
  const std::string cut = dir_->file("cut");
  fs::create_directories(cut);
  fs::copy_file(out() + "/map.ply", cut + "/map.ply");
  const std::string keyframes = test::readText(out() + "/keyframes.tum");
  dir_->write("cut/keyframes.tum", keyframes.substr(0, keyframes.find('\n') + 1));  // the first
  const std::string cut_out = dir_->file("cut_out");
  const test::RunResult wrong = test::runStorey(
      "storeys " + test::shellQuoted(cut) + " -o " + test::shellQuoted(cut_out), scratch);
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find("map.ply: vertex "), std::string::npos) << wrong.err;
  EXPECT_NE(wrong.err.find("is not one of keyframes.tum's"), std::string::npos) << wrong.err;
  EXPECT_FALSE(fs::exists(cut_out));
}

}  // namespace
}  // namespace storey
