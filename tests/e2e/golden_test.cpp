// `storey run` on the tiny preset writes the same bytes as the golden files
// in tests/golden/tiny (see its README: a behaviour-keeping change must keep
// them; a change meant to alter results regenerates them in its commit).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/run_storey.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

/// "line N: <expected> | <actual>" for the first line that differs.
std::string firstDifference(const std::string& expected, const std::string& actual) {
  std::istringstream e(expected), a(actual);
  std::string le, la;
  for (int line = 1;; ++line) {
    const bool more_e = static_cast<bool>(std::getline(e, le));
    const bool more_a = static_cast<bool>(std::getline(a, la));
    if (!more_e && !more_a) return "same lines (line endings differ?)";
    if (le != la || more_e != more_a)
      return "line " + std::to_string(line) + ": expected '" + le + "', got '" + la + "'";
  }
}

/// Runs `storey run --preset tiny --no-render EXTRA` into `out` and checks
/// the golden files.
void expectGoldenRun(const test::TempDir& dir, const std::string& out, const std::string& extra) {
  const std::filesystem::path golden =
      std::filesystem::path(STOREY_SOURCE_DIR) / "tests/golden/tiny";
  const test::RunResult run = test::runStorey(
      "run --preset tiny --no-render -o " + test::shellQuoted(out) + extra, dir.path().string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* name : {"trajectory.tum", "keyframes.tum", "planes.json", "storeys.json"}) {
    const std::string expected = test::readText((golden / name).string());
    ASSERT_FALSE(expected.empty()) << "golden file missing: " << (golden / name);
    const std::string actual = test::readText((std::filesystem::path(out) / name).string());
    EXPECT_TRUE(expected == actual)
        << name << extra << " differs from the golden file, " << firstDifference(expected, actual);
  }
}

TEST(Golden, TinyPresetWritesTheGoldenFiles) {
  test::TempDir dir;
  expectGoldenRun(dir, dir.file("out"), "");
}

// Issue 23: the same bytes whatever the number of threads (by default the
// log is read ahead on a second thread, input.read_ahead_scans).
TEST(Golden, OneThreadWritesTheSameBytes) {
  test::TempDir dir;
  const std::string one = dir.file("one"), all = dir.file("all");
  expectGoldenRun(dir, one, " --threads 1");
  expectGoldenRun(dir, all, " --threads 2");
  for (const char* name : {"odometry.tum", "map.las", "map.ply", "map.pcd"}) {
    const std::string a = test::readText(one + "/" + name);
    ASSERT_FALSE(a.empty()) << name;
    EXPECT_TRUE(a == test::readText(all + "/" + name)) << name << " differs";
  }
}

}  // namespace
}  // namespace storey
