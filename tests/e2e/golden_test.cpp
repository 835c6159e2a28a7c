// `storey run` on the tiny preset writes the same bytes as the golden files
// in tests/golden/tiny (see its README: a behaviour-keeping change must keep
// them; a change meant to alter results regenerates them in its commit).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

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

/// FNV-1a (64 bit) of a file's bytes, as 16 hex digits ("" when unreadable).
std::string fingerprint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::uint64_t h = 1469598103934665603ull;
  std::vector<char> buffer(1 << 20);
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buffer[static_cast<std::size_t>(i)]);
      h *= 1099511628211ull;
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

/// Runs `storey run --preset tiny --no-render EXTRA` into `out` and checks
/// the golden files. The simulator's input is not the same bytes on every
/// CPU (Embree and libm choose their kernels by the instruction set), so the
/// golden outputs are compared only when the simulated bag is the one they
/// were made from (its fingerprint in tests/golden/tiny/simulation.fnv1a);
/// otherwise the test says so and the caller's own checks (1 and 2 threads
/// the same bytes) still run. Returns whether the golden files were compared.
bool expectGoldenRun(const test::TempDir& dir, const std::string& out, const std::string& extra) {
  const std::filesystem::path golden =
      std::filesystem::path(STOREY_SOURCE_DIR) / "tests/golden/tiny";
  const test::RunResult run = test::runStorey(
      "run --preset tiny --no-render -o " + test::shellQuoted(out) + extra, dir.path().string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  if (run.exit_code != 0) return false;
  std::string expected_input = test::readText((golden / "simulation.fnv1a").string());
  expected_input = expected_input.substr(0, expected_input.find_first_of(" \n"));
  const std::string input = fingerprint(out + "/simulation/simulation.bag");
  EXPECT_FALSE(input.empty()) << "no simulated bag in " << out;
  if (input != expected_input) {
    std::cout << "[  NOTE    ] this machine simulates another tiny bag (fingerprint " << input
              << ", golden " << expected_input
              << "): golden files not compared (tests/golden/README.md)\n";
    return false;
  }
  for (const char* name : {"trajectory.tum", "keyframes.tum", "planes.json", "storeys.json"}) {
    const std::string expected = test::readText((golden / name).string());
    EXPECT_FALSE(expected.empty()) << "golden file missing: " << (golden / name);
    const std::string actual = test::readText((std::filesystem::path(out) / name).string());
    EXPECT_TRUE(expected == actual)
        << name << extra << " differs from the golden file, " << firstDifference(expected, actual);
  }
  return true;
}

TEST(Golden, TinyPresetWritesTheGoldenFiles) {
  test::TempDir dir;
  if (!expectGoldenRun(dir, dir.file("out"), ""))
    GTEST_SKIP() << "the simulated input differs from the golden files' (another CPU)";
}

// Issue 23: the same bytes whatever the number of threads (by default the
// log is read ahead on a second thread, input.read_ahead_scans).
TEST(Golden, OneThreadWritesTheSameBytes) {
  test::TempDir dir;
  const std::string one = dir.file("one"), all = dir.file("all");
  expectGoldenRun(dir, one, " --threads 1");
  expectGoldenRun(dir, all, " --threads 2");
  for (const char* name : {"trajectory.tum", "keyframes.tum", "planes.json", "storeys.json",
                           "odometry.tum", "map.las", "map.ply", "map.pcd"}) {
    const std::string a = test::readText(one + "/" + name);
    ASSERT_FALSE(a.empty()) << name;
    EXPECT_TRUE(a == test::readText(all + "/" + name)) << name << " differs";
  }
}

}  // namespace
}  // namespace storey
