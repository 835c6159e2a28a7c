// The --fault texts (sim/sim_faults.h): each kind read back as written, the
// samples and scans each one touches, and a clear error for a bad text.
#include "sim/sim_faults.h"

#include <gtest/gtest.h>

#include "common/error.h"

namespace storey::sim {
namespace {

TEST(SimFaults, EachKindIsReadAndWrittenBack) {
  for (const std::string text :
       {"imu_spike@5", "imu_gap@12+0.5", "lidar_gap@11+1", "imu_saturation@12+0.2",
        "occlusion@11+2", "imu_clock_jump@12+2", "imu_clock_jump@12-2", "lidar_clock_jump@12-0.5",
        "duplicate@8+2", "reorder@8+2", "nan@8+2"}) {
    EXPECT_EQ(toString(parseSimFault(text)), text);
  }
  const SimFault jump = parseSimFault("lidar_clock_jump@12-0.5");
  EXPECT_EQ(jump.kind, SimFaultKind::kLidarClockJump);
  EXPECT_DOUBLE_EQ(jump.time, 12.0);
  EXPECT_DOUBLE_EQ(jump.step, -0.5);
}

TEST(SimFaults, ABadTextNamesWhatIsWrong) {
  const auto message = [](const std::string& text) {
    try {
      parseSimFault(text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("imu_clock_jump@12").find("expected imu_clock_jump@T+S or @T-S"),
            std::string::npos);
  EXPECT_NE(message("imu_clock_jump@12+0").find("not a step in seconds other than 0"),
            std::string::npos);
  EXPECT_NE(message("imu_clock_jump@12+-1").find("not a step"), std::string::npos);
  EXPECT_NE(message("occlusion@11").find("expected occlusion@T+D"), std::string::npos);
  EXPECT_NE(message("occlusion@-1+2").find("is not a time >= 0"), std::string::npos);
  EXPECT_NE(message("knock@1").find("unknown fault 'knock'"), std::string::npos);
}

TEST(SimFaults, SamplesAndScansTouched) {
  const std::vector<SimFault> faults = {
      parseSimFault("imu_saturation@1+0.01"), parseSimFault("imu_clock_jump@2+0.5"),
      parseSimFault("occlusion@3+1"), parseSimFault("lidar_clock_jump@4-1")};
  std::vector<double> stamps;
  for (int k = 0; k < 1000; ++k) stamps.push_back(k * 0.005);
  const SampleFaults f = imuSampleFaults(faults, stamps);
  for (int k = 0; k < 1000; ++k) {
    const double t = stamps[k];
    EXPECT_EQ(f.saturate[k] != 0, t >= 1.0 && t <= 1.01 + 1e-12) << t;
    EXPECT_EQ(f.shift_ns[k], t >= 2.0 ? 500'000'000 : 0) << t;
    EXPECT_EQ(f.drop[k] + f.spike[k], 0);
  }
  EXPECT_FALSE(inOcclusion(faults, 2.99));
  EXPECT_TRUE(inOcclusion(faults, 3.5));
  EXPECT_EQ(lidarClockShiftNs(faults, 3.9), 0);
  EXPECT_EQ(lidarClockShiftNs(faults, 4.0), -1'000'000'000);
  EXPECT_TRUE(hasFault(faults, SimFaultKind::kOcclusion));
  EXPECT_FALSE(hasFault(faults, SimFaultKind::kLidarGap));
}

TEST(SimFaults, RepeatsReorderAndNanTouchTheirWindowOnly) {
  const std::vector<SimFault> faults = {parseSimFault("duplicate@1+0.1"),
                                        parseSimFault("reorder@2+0.1"), parseSimFault("nan@3+0.5")};
  std::vector<double> stamps;
  for (int k = 0; k < 1000; ++k) stamps.push_back(k * 0.005);
  const SampleFaults f = imuSampleFaults(faults, stamps);
  int duplicates = 0, late = 0, nan = 0;
  for (int k = 0; k < 1000; ++k) {
    const double t = stamps[k];
    EXPECT_EQ(f.duplicate[k] != 0, t >= 1.0 && t <= 1.1 + 1e-12) << t;
    if (f.late[k]) {
      EXPECT_TRUE(t >= 2.0 && t <= 2.1 + 1e-12) << t;
    }
    if (f.nan[k]) {
      EXPECT_TRUE(t >= 3.0 && t <= 3.5 + 1e-12) << t;
    }
    duplicates += f.duplicate[k];
    late += f.late[k];
    nan += f.nan[k];
  }
  EXPECT_EQ(duplicates, 21);  // 1.000 .. 1.100 s at 200 Hz
  EXPECT_EQ(late, 11);        // every other one of 21
  EXPECT_EQ(nan, 3);          // every 40th of 101
  EXPECT_TRUE(inFault(faults, SimFaultKind::kNan, 3.2));
  EXPECT_FALSE(inFault(faults, SimFaultKind::kNan, 3.6));
  EXPECT_TRUE(inFault(faults, SimFaultKind::kDuplicate, 1.05));
}

}  // namespace
}  // namespace storey::sim
