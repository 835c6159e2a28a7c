#pragma once
/// Paths of the real recordings (../shared/data/real) and small readers of
/// their reference files.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace storey::test {

inline std::string realData(const std::string& relative) {
  return std::string(STOREY_REAL_DATA_DIR) + "/" + relative;
}

/// VeloView's expected-output file (.expected.test): frame count, point
/// counts of some frames, sample points of one frame.
struct VeloViewExpected {
  int frame_count = 0;
  std::vector<std::pair<int, int>> point_counts;  ///< (frame, points)
  int sample_frame = -1;
  struct Sample {
    int index;
    double x, y, z;
    int intensity;
    int last;  ///< the last column (0 in every sample)
  };
  std::vector<Sample> samples;
};
VeloViewExpected readVeloViewExpected(const std::string& path);

}  // namespace storey::test
