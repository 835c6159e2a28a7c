#include "common/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "common/error.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

std::size_t countFiles(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir),
                                                std::filesystem::directory_iterator()));
}

TEST(AtomicFile, WritesContent) {
  test::TempDir dir;
  const std::string path = dir.file("out.txt");
  writeFileAtomically(path, "hello\n");
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "hello\n");
  EXPECT_EQ(countFiles(dir.path()), 1u);
}

TEST(AtomicFile, FailureLeavesNothingAndKeepsOldFile) {
  test::TempDir dir;
  const std::string path = dir.write("out.txt", "old");
  EXPECT_THROW(writeFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "half";
                                     throw Error("boom");
                                   }),
               Error);
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "old");
  EXPECT_EQ(countFiles(dir.path()), 1u);
}

TEST(AtomicFile, UnwritableDirectoryIsNamed) {
  try {
    writeFileAtomically("/nonexistent-dir/x.txt", "x");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.txt"), std::string::npos);
  }
}

TEST(AtomicFile, StaleTemporariesAreThoseOfProcessesThatAreGone) {
  test::TempDir dir;
  const pid_t gone = fork();  // a process that has ended: its pid is free
  ASSERT_GE(gone, 0);
  if (gone == 0) _exit(0);
  waitpid(gone, nullptr, 0);
  const std::string dead = std::to_string(gone), self = std::to_string(::getpid());
  std::filesystem::create_directories(dir.path() / "storeys");
  for (const std::string& name : std::vector<std::string>{
           "map.ply.tmp-" + dead + "-0", "storeys/storey_0.las.tmp-" + dead + "-12",
           "trajectory.tum.tmp-" + self + "-3", "report.json.tmp-1-0", "notes.tmp-x-1",
           "a.tmp-" + dead + "-", "b.tmp-12345678901-0", "plain.txt"})
    dir.write(name, "x");
  EXPECT_EQ(removeStaleTemporaries(dir.path().string()), 2u);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / ("map.ply.tmp-" + dead + "-0")));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / ("storeys/storey_0.las.tmp-" + dead + "-12")));
  EXPECT_EQ(countFiles(dir.path()), 7u) << "this process's, pid 1's and what is no temporary stay";
}

}  // namespace
}  // namespace storey
