// The MCAP and rosbag2 sqlite3 containers: what the simulator's writers
// write reads back (chunked or not, every compression, with or without the
// summary), and damaged files end with one line naming the file and the
// problem (`storey info`, exit 1), never a crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/mcap_file.h"
#include "io/ros2_bag.h"
#include "io/ros_message_codec.h"
#include "io/sqlite_storage.h"
#include "sim/db3_writer.h"
#include "sim/mcap_writer.h"
#include "support/run_storey.h"
#include "support/temp_dir.h"

namespace storey {
namespace {

using sim::McapCompression;

std::vector<std::uint8_t> imuBytes(std::int64_t t_ns) {
  ImuSample s;
  s.stamp_ns = t_ns;
  s.gyro = {0.01, 0.02, 0.03};
  s.accel = {0.0, 0.0, 9.81};
  return encodeImu(s, "imu", 1e-6, 1e-4, nullptr, nullptr, WireFormat::kCdr);
}

/// 200 IMU messages (10 ms apart) on /imu/data, small chunks so there are several.
void writeImuLog(sim::Ros2StorageWriter& w) {
  w.addTopic(1, "/imu/data", "sensor_msgs/msg/Imu",
             rosMessageDefinition(kImuType, WireFormat::kCdr));
  for (int i = 0; i < 200; ++i) {
    const std::int64_t t = 1'700'000'000'000'000'000LL + i * 10'000'000LL;
    w.write(1, t, imuBytes(t));
  }
  w.close();
}

std::int64_t countMessages(MessageStorage& storage) {
  storage.select({});
  RawMessage m;
  std::int64_t n = 0;
  while (storage.next(m)) {
    const ImuMessage imu = decodeImu(m.data.data(), m.data.size(), WireFormat::kCdr);
    EXPECT_EQ(imu.sample.stamp_ns, m.log_time_ns);
    ++n;
  }
  return n;
}

std::string writeMcap(const test::TempDir& dir, const std::string& name,
                      const sim::McapWriterOptions& options) {
  const std::string path = dir.file(name);
  auto writer = sim::openMcapWriter(path, options);
  writeImuLog(*writer);
  return path;
}

std::vector<char> readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}
void writeAll(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(McapContainer, EveryLayoutReadsBack) {
  test::TempDir dir;
  for (auto compression : {McapCompression::kNone, McapCompression::kZstd, McapCompression::kLz4}) {
    for (bool chunked : {true, false}) {
      for (bool summary : {true, false}) {
        sim::McapWriterOptions o;
        o.compression = compression;
        o.chunked = chunked;
        o.summary = summary;
        o.chunk_bytes = 4000;
        const std::string path = writeMcap(dir, "log.mcap", o);
        auto storage = openMcapStorage(path);
        ASSERT_EQ(storage->topics().size(), 1u);
        EXPECT_EQ(storage->topics()[0].type, "sensor_msgs/msg/Imu");
        EXPECT_EQ(storage->topics()[0].encoding, "cdr");
        EXPECT_EQ(storage->topics()[0].count, 200) << chunked << summary;
        EXPECT_EQ(countMessages(*storage), 200);
      }
    }
  }
}

TEST(McapContainer, FileCutShortYieldsItsCompleteChunks) {
  test::TempDir dir;
  sim::McapWriterOptions o;
  o.chunk_bytes = 4000;
  const std::string path = writeMcap(dir, "log.mcap", o);
  auto bytes = readAll(path);
  bytes.resize(bytes.size() / 2);
  const std::string cut = dir.file("cut.mcap");
  writeAll(cut, bytes);
  auto storage = openMcapStorage(cut);
  const std::int64_t n = countMessages(*storage);
  EXPECT_GT(n, 20);
  EXPECT_LT(n, 200);
  EXPECT_EQ(storage->topics()[0].count, n);
}

/// `storey info FILE` fails with exit 1 and one stderr line naming the file and `problem`.
void expectOneLineError(const std::string& file, const std::string& problem,
                        const test::TempDir& dir) {
  const auto r = test::runStorey("info " + test::shellQuoted(file), dir.path().string());
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(McapContainer, DamagedFilesAreOneLineErrors) {
  test::TempDir dir;
  sim::McapWriterOptions o;
  o.compression = McapCompression::kNone;
  const std::string plain = writeMcap(dir, "plain.mcap", o);
  auto bytes = readAll(plain);
  // A bit flipped inside the (uncompressed) chunk: its CRC does not match.
  auto flipped = bytes;
  flipped[bytes.size() / 3] ^= 0x10;
  writeAll(dir.file("flipped.mcap"), flipped);
  expectOneLineError(dir.file("flipped.mcap"), "CRC mismatch", dir);

  o.compression = McapCompression::kZstd;
  const std::string zstd = writeMcap(dir, "zstd.mcap", o);
  bytes = readAll(zstd);
  const std::string tag = "zstd";
  auto it = std::search(bytes.begin(), bytes.end(), tag.begin(), tag.end());
  ASSERT_NE(it, bytes.end());
  std::copy_n("brot", 4, it);
  writeAll(dir.file("unknown.mcap"), bytes);
  expectOneLineError(dir.file("unknown.mcap"), "unknown chunk compression 'brot'", dir);

  // A channel referring to a schema the file does not define.
  std::vector<char> hand(kMcapMagic, kMcapMagic + kMcapMagicSize);
  auto record = [&](std::uint8_t op, const std::vector<std::uint8_t>& content) {
    hand.push_back(static_cast<char>(op));
    for (int k = 0; k < 8; ++k) hand.push_back(static_cast<char>(content.size() >> (8 * k)));
    hand.insert(hand.end(), content.begin(), content.end());
  };
  record(0x01, {0, 0, 0, 0, 0, 0, 0, 0});  // Header
  record(0x04,
         {1, 0, 5, 0, 2, 0, 0, 0, '/', 'x', 3, 0, 0, 0, 'c', 'd', 'r', 0, 0, 0, 0});  // Channel
  writeAll(dir.file("noschema.mcap"), hand);
  expectOneLineError(dir.file("noschema.mcap"), "refers to schema 5", dir);

  // Nothing but the magic and a header: an empty log.
  std::vector<char> empty(hand.begin(), hand.begin() + kMcapMagicSize + 9 + 8);

  // A zstd chunk of 12 bytes claiming 3 GiB: refused before allocating the 3 GiB.
  std::vector<char> huge(empty);
  std::vector<std::uint8_t> chunk(16, 0);                  // start and end time
  for (int k = 0; k < 8; ++k) chunk.push_back(static_cast<std::uint8_t>((3ULL << 30) >> (8 * k)));
  chunk.insert(chunk.end(), {0, 0, 0, 0, 4, 0, 0, 0, 'z', 's', 't', 'd', 12, 0, 0, 0, 0, 0, 0, 0});
  chunk.insert(chunk.end(), {0x28, 0xb5, 0x2f, 0xfd, 0, 0, 0, 0, 0, 0, 0, 0});
  hand.swap(huge);
  record(0x06, chunk);
  hand.swap(huge);
  writeAll(dir.file("huge.mcap"), huge);
  expectOneLineError(dir.file("huge.mcap"), "more than zstd can expand to", dir);
  writeAll(dir.file("empty.mcap"), empty);
  const auto r = test::runStorey("run " + test::shellQuoted(dir.file("empty.mcap")) + " -o " +
                                     test::shellQuoted(dir.file("out")) + " --no-render",
                                 dir.path().string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no point cloud topic"), std::string::npos) << r.err;
}

TEST(Db3Container, ReadsBackAndDamageIsAnError) {
  test::TempDir dir;
  const std::string path = dir.file("log.db3");
  {
    auto writer = sim::openDb3Writer(path);
    writeImuLog(*writer);
  }
  auto storage = openSqliteStorage({path});
  ASSERT_EQ(storage->topics().size(), 1u);
  EXPECT_EQ(storage->topics()[0].count, 200);
  EXPECT_EQ(countMessages(*storage), 200);

  // A split bag: two files merged in time order.
  const std::string second = dir.file("second.db3");
  {
    auto writer = sim::openDb3Writer(second);
    writeImuLog(*writer);
  }
  auto split = openSqliteStorage({path, second});
  EXPECT_EQ(split->topics()[0].count, 400);
  split->select({});
  RawMessage m;
  std::int64_t last = 0, n = 0;
  while (split->next(m)) {
    EXPECT_GE(m.log_time_ns, last);
    last = m.log_time_ns;
    ++n;
  }
  EXPECT_EQ(n, 400);

  auto bytes = readAll(path);
  auto truncated = bytes;
  truncated.resize(bytes.size() / 2);
  writeAll(dir.file("truncated.db3"), truncated);
  const auto r =
      test::runStorey("info " + test::shellQuoted(dir.file("truncated.db3")), dir.path().string());
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.err.find("truncated.db3"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;

  auto flipped = bytes;
  for (std::size_t i = 100; i < bytes.size(); i += 997) flipped[i] ^= 0x5A;
  writeAll(dir.file("flipped.db3"), flipped);
  const auto f =
      test::runStorey("info " + test::shellQuoted(dir.file("flipped.db3")), dir.path().string());
  EXPECT_NE(f.exit_code, -1);  // no crash (a flip may land in message bytes and go unnoticed)
  if (f.exit_code != 0) {
    EXPECT_EQ(f.exit_code, 1);
    EXPECT_NE(f.err.find("flipped.db3"), std::string::npos) << f.err;
  }

  // Only a topic of a type Storey does not read.
  const std::string other = dir.file("other.db3");
  {
    auto writer = sim::openDb3Writer(other);
    writer->addTopic(1, "/odom", "nav_msgs/msg/Odometry", "");
    writer->write(1, 1, {0, 1, 0, 0});
    writer->close();
  }
  const auto o = test::runStorey("run " + test::shellQuoted(other) + " -o " +
                                     test::shellQuoted(dir.file("out")) + " --no-render",
                                 dir.path().string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("other.db3"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("nav_msgs/msg/Odometry"), std::string::npos) << o.err;
}

}  // namespace
}  // namespace storey
