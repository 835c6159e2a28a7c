#include "common/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

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

}  // namespace
}  // namespace storey
