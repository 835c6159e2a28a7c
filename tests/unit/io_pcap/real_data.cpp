#include "real_data.h"

#include <fstream>
#include <sstream>

namespace storey::test {

VeloViewExpected readVeloViewExpected(const std::string& path) {
  VeloViewExpected e;
  std::ifstream in(path);
  std::string line;
  int frame = -1;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    if (!(words >> key)) continue;
    if (key == "frame_count") {
      words >> e.frame_count;
    } else if (key == "frame") {
      words >> frame;
    } else if (key == "point_count") {
      int n = 0;
      words >> n;
      bool seen = false;
      for (const auto& [f, count] : e.point_counts) seen = seen || f == frame;
      if (!seen) e.point_counts.push_back({frame, n});
    } else if (key == "point_values") {
      VeloViewExpected::Sample s{};
      words >> s.index >> s.x >> s.y >> s.z >> s.intensity >> s.last;
      e.sample_frame = frame;
      e.samples.push_back(s);
    }
  }
  return e;
}

}  // namespace storey::test
