// Feeds each input of tests/data/fuzz/<target>/ to the code of the fuzz
// target that found it (fuzz/targets/<target>.cpp, compiled into this test):
// it must return (storey::Error is caught there as the expected outcome);
// a crash, another exception or, in the asan preset, a sanitizer report
// fails the test. See docs/testing.md.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#define STOREY_FUZZ_DECLARE(name) \
  extern "C" int storeyFuzz_##name(const std::uint8_t* data, std::size_t size);
STOREY_FUZZ_DECLARE(rosbag)
STOREY_FUZZ_DECLARE(pointcloud2)
STOREY_FUZZ_DECLARE(ros_messages)
STOREY_FUZZ_DECLARE(pcap)
STOREY_FUZZ_DECLARE(velodyne_packet)
STOREY_FUZZ_DECLARE(pcd)
STOREY_FUZZ_DECLARE(imu_csv)
STOREY_FUZZ_DECLARE(db3)
STOREY_FUZZ_DECLARE(mcap)
STOREY_FUZZ_DECLARE(rosbag2_metadata)
STOREY_FUZZ_DECLARE(veloview_xml)
STOREY_FUZZ_DECLARE(tum)
STOREY_FUZZ_DECLARE(planes_json)
STOREY_FUZZ_DECLARE(storeys_json)
STOREY_FUZZ_DECLARE(ply)
STOREY_FUZZ_DECLARE(config_yaml)
STOREY_FUZZ_DECLARE(calibration_yaml)

namespace {

namespace fs = std::filesystem;
using FuzzFn = int (*)(const std::uint8_t*, std::size_t);

const std::map<std::string, FuzzFn>& targets() {
#define STOREY_FUZZ_ENTRY(name) {#name, &storeyFuzz_##name},
  static const std::map<std::string, FuzzFn> all = {
      STOREY_FUZZ_ENTRY(rosbag) STOREY_FUZZ_ENTRY(pointcloud2) STOREY_FUZZ_ENTRY(ros_messages)
          STOREY_FUZZ_ENTRY(pcap) STOREY_FUZZ_ENTRY(velodyne_packet) STOREY_FUZZ_ENTRY(pcd)
              STOREY_FUZZ_ENTRY(imu_csv) STOREY_FUZZ_ENTRY(db3) STOREY_FUZZ_ENTRY(mcap)
                  STOREY_FUZZ_ENTRY(rosbag2_metadata) STOREY_FUZZ_ENTRY(veloview_xml)
                      STOREY_FUZZ_ENTRY(tum) STOREY_FUZZ_ENTRY(planes_json)
                          STOREY_FUZZ_ENTRY(storeys_json) STOREY_FUZZ_ENTRY(ply)
                              STOREY_FUZZ_ENTRY(config_yaml) STOREY_FUZZ_ENTRY(calibration_yaml)};
#undef STOREY_FUZZ_ENTRY
  return all;
}

fs::path dataDir() {
  return fs::path(STOREY_SOURCE_DIR) / "tests" / "data" / "fuzz";
}

TEST(FuzzRegressions, EveryTargetOfTheFuzzBuildIsHere) {
  std::stringstream names(STOREY_FUZZ_TARGETS);
  std::string name;
  while (std::getline(names, name, ',')) EXPECT_EQ(targets().count(name), 1u) << name;
}

TEST(FuzzRegressions, EveryFoundInputEndsInAStoreyErrorOrNothing) {
  int inputs = 0;
  if (!fs::is_directory(dataDir())) GTEST_SKIP() << "no " << dataDir();
  for (const auto& folder : fs::directory_iterator(dataDir())) {
    if (!folder.is_directory()) continue;
    const std::string target = folder.path().filename().string();
    ASSERT_EQ(targets().count(target), 1u)
        << "tests/data/fuzz/" << target << ": no such fuzz target";
    for (const auto& file : fs::directory_iterator(folder.path())) {
      std::ifstream in(file.path(), std::ios::binary);
      const std::vector<char> bytes{std::istreambuf_iterator<char>(in),
                                    std::istreambuf_iterator<char>()};
      SCOPED_TRACE(file.path().string());
      targets().at(target)(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++inputs;
    }
  }
  RecordProperty("inputs", inputs);
}

}  // namespace
