// `storey info` on a real capture: the sensor, its spin rate and the scans.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "real_data.h"

namespace storey {
namespace {

std::string run(const std::string& command, int& status) {
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return out;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) out += buffer.data();
  status = pclose(pipe);
  return out;
}

TEST(PcapInfoCli, ShowsSensorRateAndScans) {
  const std::string pcap = test::realData("veloview-vlp16-indoor/vlp-16-test-90deg-1-50-frames.pcap");
  if (!std::filesystem::exists(pcap)) GTEST_SKIP() << "real data absent: " << pcap;
  int status = -1;
  const std::string out = run(std::string(STOREY_BINARY) + " info " + pcap, status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("Velodyne pcap"), std::string::npos) << out;
  EXPECT_NE(out.find("VLP-16"), std::string::npos) << out;
  EXPECT_NE(out.find("rotation     19.9"), std::string::npos) << out;
  EXPECT_NE(out.find("scan        52"), std::string::npos) << out;
  EXPECT_NE(out.find("--imu-csv"), std::string::npos) << out;  // no IMU: says how to give one
}

}  // namespace
}  // namespace storey
