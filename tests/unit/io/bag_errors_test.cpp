// Bad input: every case ends with a one-line storey::Error naming the file
// (and what is wrong), never with a crash.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "common/error.h"
#include "common/log.h"
#include "config/config.h"
#include "io/log_reader.h"
#include "io/log_summary.h"
#include "io/rosbag_structure.h"
#include "unit/io/bag_fixtures.h"

namespace storey {
namespace {

using test::TestBagWriter;

constexpr std::int64_t kT0 = 1'700'000'000'000'000'000;
constexpr std::int64_t kMs = 1'000'000;

/// Opens and reads the whole log; returns the error message ("" when it read fine).
std::string readError(const std::string& path, const Config& config = Config{}) {
  try {
    const auto reader = openLog(path, config.input, config.sensor);
    LogMessage m;
    while (reader->next(m)) {
    }
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string summaryError(const std::string& path) {
  try {
    summarizeLog(path, InputConfig{});
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

::testing::AssertionResult namesFileInOneLine(const std::string& message, const std::string& path,
                                              const std::string& what) {
  if (message.empty()) return ::testing::AssertionFailure() << "no error for " << path;
  if (message.find('\n') != std::string::npos) {
    return ::testing::AssertionFailure() << "error spans lines: " << message;
  }
  if (message.rfind(path, 0) != 0) {
    return ::testing::AssertionFailure() << "error does not start with the file: " << message;
  }
  if (message.find(what) == std::string::npos) {
    return ::testing::AssertionFailure() << "error lacks '" << what << "': " << message;
  }
  return ::testing::AssertionSuccess();
}

class BagErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir("bag_errors");
    setLogSink([](LogLevel, const std::string&) {});
  }
  void TearDown() override {
    setLogSink(nullptr);
    std::filesystem::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }

  /// A valid bag of several uncompressed chunks (clouds of ~2 kB, 4 kB chunks).
  std::string multiChunkBag() {
    test::VelodyneImuBag spec;
    spec.chunk_bytes = 4096;
    const std::string file = path("multi_chunk.bag");
    test::writeVelodyneImuBag(file, spec);
    return file;
  }

  std::string dir_;
};

TEST_F(BagErrors, MissingFile) {
  const std::string file = path("does_not_exist.bag");
  EXPECT_TRUE(namesFileInOneLine(readError(file), file, "no such file"));
  EXPECT_TRUE(namesFileInOneLine(summaryError(file), file, "no such file"));
}

TEST_F(BagErrors, Directory) {
  EXPECT_TRUE(namesFileInOneLine(readError(dir_), dir_, "directory"));
}

TEST_F(BagErrors, EmptyFile) {
  const std::string file = path("empty.bag");
  test::writeFileBytes(file, "");
  EXPECT_TRUE(namesFileInOneLine(readError(file), file, "empty file"));
}

TEST_F(BagErrors, NonBagFileWhateverItsName) {
  const std::string file = path("notes.bag");
  test::writeFileBytes(file, "timestamp,gx,gy,gz\n0.0,0,0,0\n");
  EXPECT_TRUE(namesFileInOneLine(readError(file), file, "unknown log format"));
  EXPECT_TRUE(namesFileInOneLine(summaryError(file), file, "unknown log format"));
}

TEST_F(BagErrors, BagIsDetectedByContentNotExtension) {
  const std::string file = path("recording.dat");
  test::writeVelodyneImuBag(file, test::VelodyneImuBag{});
  EXPECT_EQ(readError(file), "");
}

TEST_F(BagErrors, UnsupportedBagVersion) {
  const std::string file = path("old.bag");
  test::writeFileBytes(file, std::string("#ROSBAG V1.2\n") + std::string(4096, ' '));
  EXPECT_TRUE(namesFileInOneLine(readError(file), file, "unsupported ROS bag version '1.2'"));
}

TEST_F(BagErrors, MagicOnly) {
  const std::string file = path("magic_only.bag");
  test::writeFileBytes(file, "#ROSBAG V2.0\n");
  EXPECT_TRUE(namesFileInOneLine(readError(file), file, "damaged or truncated ROS bag"));
  const std::string partial = path("partial_magic.bag");
  test::writeFileBytes(partial, "#ROSB");
  EXPECT_TRUE(namesFileInOneLine(readError(partial), partial, "truncated ROS bag"));
}

TEST_F(BagErrors, TruncatedInsideAChunk) {
  const std::string full = multiChunkBag();
  const RosbagStructure structure = checkRosbagStructure(full);
  // The fixture has several chunks; cut inside the third one.
  ASSERT_GE(structure.chunk_positions.size(), 4u);
  const std::uint64_t cut = structure.chunk_positions[2] + 1000;
  ASSERT_LT(cut, structure.chunk_positions[3]);
  ASSERT_LT(cut, structure.index_pos);
  const std::string file = path("truncated.bag");
  test::truncatedCopy(full, file, cut);
  const std::string message = readError(file);
  EXPECT_TRUE(namesFileInOneLine(message, file, "truncated"));
  EXPECT_NE(message.find("index should start at byte " + std::to_string(structure.index_pos)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(std::to_string(cut) + " bytes"), std::string::npos) << message;
  EXPECT_TRUE(namesFileInOneLine(summaryError(file), file, "truncated"));
}

TEST_F(BagErrors, TruncatedAtEveryPlaceIsAnError) {
  const std::string full = multiChunkBag();
  const std::uint64_t size = std::filesystem::file_size(full);
  const std::string file = path("cut.bag");
  int cases = 0;
  for (std::uint64_t cut = 0; cut < size; cut += (cut < 5000 ? 7 : 211)) {
    test::truncatedCopy(full, file, cut);
    const std::string message = readError(file);
    ASSERT_FALSE(message.empty()) << "cut at " << cut;
    ASSERT_EQ(message.rfind(file, 0), 0u) << message;
    ASSERT_EQ(message.find('\n'), std::string::npos) << message;
    ++cases;
  }
  EXPECT_GT(cases, 100);
}

TEST_F(BagErrors, CorruptedBytesNeverCrash) {
  // Flipped bytes anywhere in uncompressed and compressed bags: the read either
  // succeeds or ends with a storey::Error naming the file; librosbag alone
  // crashes (SIGSEGV) on some of these.
  for (const auto compression : {test::TestCompression::kNone, test::TestCompression::kLz4}) {
    test::VelodyneImuBag spec;
    spec.chunk_bytes = 4096;
    spec.compression = compression;
    spec.scans = 4;
    const std::string full = path("clean.bag");
    test::writeVelodyneImuBag(full, spec);
    const std::string bytes = test::readFileBytes(full);
    const std::string file = path("flipped.bag");
    std::mt19937 rng(compression == test::TestCompression::kNone ? 7 : 8);
    int errors = 0;
    for (int trial = 0; trial < 600; ++trial) {
      std::string damaged = bytes;
      const std::size_t at = rng() % damaged.size();
      damaged[at] = static_cast<char>(damaged[at] ^ static_cast<char>(1 + rng() % 255));
      test::writeFileBytes(file, damaged);
      const std::string message = readError(file);
      if (!message.empty()) {
        ++errors;
        ASSERT_EQ(message.rfind(file, 0), 0u) << "byte " << at << ": " << message;
        ASSERT_EQ(message.find('\n'), std::string::npos) << message;
      }
      const std::string summary_message = summaryError(file);
      if (!summary_message.empty()) {
        ASSERT_EQ(summary_message.rfind(file, 0), 0u) << summary_message;
      }
    }
    EXPECT_GT(errors, 0);
  }
}

TEST_F(BagErrors, UnindexedBag) {
  const std::string full = multiChunkBag();
  std::string bytes = test::readFileBytes(full);
  // What an interrupted recording leaves: a file header with index_pos = 0.
  const std::string key = "index_pos=";
  const std::size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  ASSERT_LT(at, 4096u);
  std::memset(&bytes[at + key.size()], 0, 8);
  const std::string file = path("unindexed.bag");
  test::writeFileBytes(file, bytes);
  EXPECT_TRUE(namesFileInOneLine(readError(file), file, "not indexed"));
}

TEST_F(BagErrors, BagWithoutImu) {
  const std::string file = path("no_imu.bag");
  {
    TestBagWriter bag(file);
    bag.write("/velodyne_points", kT0, test::velodyneCloud(kT0, {{5, 0, 0, 1, 0, 0}}));
    bag.writeString("/notes", kT0, "x");
  }
  const std::string message = readError(file);
  EXPECT_TRUE(namesFileInOneLine(message, file, "no IMU topic"));
  EXPECT_NE(message.find("/velodyne_points (sensor_msgs/PointCloud2, 1 messages)"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("/notes (std_msgs/String, 1 messages)"), std::string::npos) << message;
}

TEST_F(BagErrors, BagWithoutPointClouds) {
  const std::string file = path("no_points.bag");
  {
    TestBagWriter bag(file);
    test::TestImu imu;
    imu.stamp_ns = kT0;
    bag.write("/imu/data", kT0, imu);
  }
  const std::string message = readError(file);
  EXPECT_TRUE(namesFileInOneLine(message, file, "no point cloud topic"));
  EXPECT_NE(message.find("/imu/data (sensor_msgs/Imu, 1 messages)"), std::string::npos) << message;
}

TEST_F(BagErrors, EmptyBag) {
  const std::string file = path("no_messages.bag");
  { TestBagWriter bag(file); }
  EXPECT_TRUE(namesFileInOneLine(readError(file), file, "topics found: none"));
}

TEST_F(BagErrors, OverrideTopicThatDoesNotExist) {
  const std::string file = path("override.bag");
  test::writeVelodyneImuBag(file, test::VelodyneImuBag{});
  Config config;
  config.input.imu_topic = "/imu/missing";
  const std::string message = readError(file, config);
  EXPECT_TRUE(namesFileInOneLine(message, file, "/imu/missing does not exist"));
  EXPECT_NE(message.find("/imu/data"), std::string::npos);
  config.input.imu_topic = "/velodyne_points";
  EXPECT_TRUE(namesFileInOneLine(readError(file, config), file, "is not of type sensor_msgs/Imu"));
}

TEST_F(BagErrors, CloudWithoutZNamesTopicAndMessage) {
  const std::string file = path("no_z.bag");
  {
    TestBagWriter bag(file);
    for (int i = 0; i < 30; ++i) {
      test::TestImu imu;
      imu.stamp_ns = kT0 + i * 5 * kMs;
      bag.write("/imu", imu.stamp_ns, imu);
    }
    bag.write("/cloud", kT0 + 100 * kMs, test::velodyneCloud(kT0, {{5, 0, 0, 1, 0, 0}}));
    test::TestCloud no_z = test::xyzCloud(kT0 + 100 * kMs, {{1, 2, 3}});
    no_z.fields.pop_back();
    bag.write("/cloud", kT0 + 200 * kMs, no_z);
  }
  const std::string message = readError(file);
  EXPECT_TRUE(namesFileInOneLine(message, file, "/cloud message #1"));
  EXPECT_NE(message.find("no 'z' field"), std::string::npos) << message;
}

TEST_F(BagErrors, CloudWithTooFewBytes) {
  const std::string file = path("short_data.bag");
  {
    TestBagWriter bag(file);
    test::TestImu imu;
    imu.stamp_ns = kT0;
    bag.write("/imu", kT0, imu);
    test::TestCloud cloud = test::velodyneCloud(kT0, {{5, 0, 0, 1, 0, 0}, {6, 0, 0, 1, 0, 0}});
    cloud.data.resize(40);
    bag.write("/cloud", kT0, cloud);
  }
  const std::string message = readError(file);
  EXPECT_TRUE(namesFileInOneLine(message, file, "/cloud message #0"));
  EXPECT_NE(message.find("data holds 40 bytes"), std::string::npos) << message;
}

}  // namespace
}  // namespace storey
