// core/pipeline/scan_timings: the per-scan wall times of OUT/timing.csv.
#include "pipeline/scan_timings.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace storey {
namespace {

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(ScanTimings, WritesAHeaderAndOneLinePerScanInOrder) {
  const std::string path =
      (std::filesystem::path(testing::TempDir()) / "scan_timings_test.csv").string();
  ScanTimings timings;
  timings.add(1700000000.05, 12.3456, false, 0.0123);
  timings.add(1700000000.15, 9.5, true, 41.25);
  EXPECT_EQ(timings.size(), 2u);
  timings.write(path);
  const std::vector<std::string> got = lines(path);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0], "time,odometry_ms,backend_ms,keyframe");
  EXPECT_EQ(got[1], "1700000000.049999952,12.346,0.012,0");
  EXPECT_EQ(got[2], "1700000000.150000095,9.500,41.250,1");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace storey
