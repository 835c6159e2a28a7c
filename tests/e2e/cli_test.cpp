// End-to-end checks of the `storey` command line: help, subcommands, errors.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>

#include "support/temp_dir.h"

namespace storey {
namespace {

struct Result {
  int status = -1;
  std::string output;  // stdout and stderr together
};

Result runStorey(const std::string& args) {
  const std::string command = std::string(STOREY_BINARY) + " " + args + " 2>&1";
  Result result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TEST(Cli, HelpListsEverySubcommand) {
  const Result r = runStorey("--help");
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char* sub : {"run", "simulate", "info", "eval", "render", "storeys"})
    EXPECT_NE(r.output.find(sub), std::string::npos) << sub << "\n" << r.output;
}

TEST(Cli, EachSubcommandHasHelp) {
  for (const char* sub : {"run", "simulate", "info", "eval", "render", "storeys"}) {
    const Result r = runStorey(std::string(sub) + " --help");
    EXPECT_EQ(r.status, 0) << sub << "\n" << r.output;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub << "\n" << r.output;
  }
}

TEST(Cli, NoSubcommandOrUnknownOptionFails) {
  EXPECT_NE(runStorey("").status, 0);
  EXPECT_EQ(runStorey("info --bogus x").status, 1);
  EXPECT_EQ(runStorey("frobnicate").status, 1);
}

TEST(Cli, RenderOfAFolderThatIsNoRunFails) {
  test::TempDir dir;
  const Result r = runStorey("render " + dir.path().string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("trajectory.tum"), std::string::npos) << r.output;
}

TEST(Cli, BadCalibrationIsReportedWithTheKey) {
  test::TempDir dir;
  const std::string calibration = dir.write(
      "calib.yaml", "T_imu_lidar:\n  translation: [0, 0, 0]\n  rotation_xyzw: [0, 0, 0, 3]\n");
  const Result r = runStorey("run " + dir.file("missing.bag") + " --calibration " + calibration);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("T_imu_lidar.rotation_xyzw"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(calibration), std::string::npos) << r.output;
  // one line, no crash trace
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(Cli, BadConfigKeyIsNamed) {
  test::TempDir dir;
  const std::string config = dir.write("c.yaml", "input:\n  max_rnge: 50\n");
  const Result r = runStorey("run " + dir.file("missing.bag") + " -c " + config);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("input.max_rnge"), std::string::npos) << r.output;
}

TEST(Cli, MissingLogIsNamed) {
  test::TempDir dir;
  const Result r = runStorey("run " + dir.file("nope.bag") + " -o " + dir.file("out"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("nope.bag"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << "no output for a failed run";
}

}  // namespace
}  // namespace storey
