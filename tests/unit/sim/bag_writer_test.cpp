// The simulator's ROS 1 bag writer when the disk is full: one storey::Error
// naming the bag and the likely cause, never std::terminate (rosbag::Bag
// closes again in its destructor, and a second failure there aborted the
// program: `storey simulate` died on a full disk).
#include "sim/bag_writer.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <csignal>
#include <cstdlib>
#include <iostream>

#include "common/error.h"
#include "support/temp_dir.h"

namespace storey::sim {
namespace {

void writeImu(const std::string& path, BagCompression compression) {
  BagWriter writer(path, compression);
  ImuSample sample;
  sample.accel = Eigen::Vector3d(0.0, 0.0, 9.81);
  for (int i = 0; i < 100000; ++i) {
    sample.stamp_ns = 1'000'000'000 + i * 2'500'000LL;
    writer.writeImu("/imu", "imu", sample, sample.stamp_ns, 1e-6, 1e-4);
  }
  writer.close();
}

/// Exit status 0 when writing `path` fails with an Error naming it and a full disk.
[[noreturn]] void expectDiskFullError(const std::string& path, BagCompression compression) {
  std::string what = "writing " + path + " succeeded";
  try {
    writeImu(path, compression);
  } catch (const Error& e) {
    what = e.what();
  }
  const bool named =
      what.find(path + ":") != std::string::npos && what.find("disk full") != std::string::npos;
  if (!named) std::cerr << what << '\n';
  std::exit(named ? 0 : 1);
}

/// The same with the file size limited to 256 KiB (RLIMIT_FSIZE; SIGXFSZ
/// ignored so writes fail with EFBIG): the writes fail part-way, as on a
/// disk filling up.
[[noreturn]] void expectDiskFullErrorPartWay(const std::string& path, BagCompression compression) {
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit limit{};
  limit.rlim_cur = limit.rlim_max = 256 * 1024;
  setrlimit(RLIMIT_FSIZE, &limit);
  expectDiskFullError(path, compression);
}

TEST(BagWriter, AFullDiskWhenOpeningIsAnError) {
  struct stat st {};
  if (stat("/dev/full", &st) != 0) GTEST_SKIP() << "no /dev/full on this machine";
  for (const BagCompression compression : {BagCompression::kNone, BagCompression::kLz4})
    EXPECT_EXIT(expectDiskFullError("/dev/full", compression), ::testing::ExitedWithCode(0), "");
}

TEST(BagWriter, AFullDiskWhileWritingIsAnError) {
  test::TempDir dir;
  for (const BagCompression compression : {BagCompression::kNone, BagCompression::kLz4}) {
    const std::string path = dir.file(compression == BagCompression::kLz4 ? "lz4.bag" : "raw.bag");
    EXPECT_EXIT(expectDiskFullErrorPartWay(path, compression), ::testing::ExitedWithCode(0), "");
  }
}

}  // namespace
}  // namespace storey::sim
