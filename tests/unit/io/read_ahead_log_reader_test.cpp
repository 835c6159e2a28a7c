// The read-ahead reader (io/read_ahead_log_reader.h): the inner reader's
// messages in its order, its error after the messages read before it, a
// bounded queue, and a consumer that stops early.
#include "io/read_ahead_log_reader.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "common/error.h"

namespace storey {
namespace {

/// `count` messages: a scan of `i` points after every ninth IMU sample, then
/// (with `fail`) an error.
class CountingReader : public LogReader {
 public:
  CountingReader(int count, bool fail) : count_(count), fail_(fail) {}
  bool next(LogMessage& message) override {
    if (read_ == count_) {
      if (fail_) throw Error("counting.bag: damaged at message " + std::to_string(read_));
      return false;
    }
    const int i = read_++;
    if (i % 10 == 9) {
      Scan scan;
      scan.stamp_ns = i;
      scan.points.resize(static_cast<std::size_t>(i));
      message = std::move(scan);
      ++stats_.scans;
    } else {
      ImuSample sample;
      sample.stamp_ns = i;
      message = sample;
      ++stats_.imu_samples;
    }
    return true;
  }
  const LogReadStats& stats() const override { return stats_; }
  std::string describe() const override { return "counting reader"; }
  double progress() const override { return static_cast<double>(read_) / count_; }
  int read() const { return read_; }

 private:
  int count_;
  bool fail_;
  std::atomic<int> read_{0};
  LogReadStats stats_;
};

std::int64_t stampOf(const LogMessage& message) {
  if (const auto* scan = std::get_if<Scan>(&message)) return scan->stamp_ns;
  return std::get<ImuSample>(message).stamp_ns;
}

TEST(ReadAheadLogReader, GivesTheInnerReadersMessagesInOrder) {
  ReadAheadLogReader reader(std::make_unique<CountingReader>(1000, false), 2);
  EXPECT_EQ(reader.describe(), "counting reader");
  LogMessage message;
  std::int64_t expected = 0;
  while (reader.next(message)) {
    ASSERT_EQ(stampOf(message), expected);
    if (const auto* scan = std::get_if<Scan>(&message)) {
      EXPECT_EQ(scan->points.size(), static_cast<std::size_t>(expected));
    }
    EXPECT_DOUBLE_EQ(reader.progress(), (expected + 1) / 1000.0);
    ++expected;
  }
  EXPECT_EQ(expected, 1000);
  EXPECT_FALSE(reader.next(message));
  EXPECT_EQ(reader.stats().scans, 100);
  EXPECT_EQ(reader.stats().imu_samples, 900);
}

TEST(ReadAheadLogReader, AnErrorComesAfterTheMessagesReadBeforeIt) {
  ReadAheadLogReader reader(std::make_unique<CountingReader>(25, true), 4);
  LogMessage message;
  int delivered = 0;
  try {
    while (reader.next(message)) ++delivered;
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "counting.bag: damaged at message 25");
  }
  EXPECT_EQ(delivered, 25);
}

/// How many messages the inner reader has read once the thread has filled
/// the queue of a reader holding `max_scans` and `max_messages`, one taken.
int readAheadOf(int max_scans, int max_messages) {
  auto inner = std::make_unique<CountingReader>(100000, false);
  const CountingReader& counting = *inner;
  ReadAheadLogReader reader(std::move(inner), max_scans, max_messages);
  LogMessage message;
  EXPECT_TRUE(reader.next(message));
  int read = 0;
  for (int wait = 0; wait < 50; ++wait) {  // until it stops growing
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (counting.read() == read && read > 1) break;
    read = counting.read();
  }
  return counting.read();
}

TEST(ReadAheadLogReader, ReadsOnlyAFewScansAhead) {
  // Message 0 taken; queued 1..29 (up to the third scan, 29); the thread
  // holds message 30 until a scan is taken.
  EXPECT_EQ(readAheadOf(3, 8192), 31);
  // At most 5 messages queued (1..5), the sixth held.
  EXPECT_EQ(readAheadOf(100, 5), 7);
}

TEST(ReadAheadLogReader, AConsumerMayStopEarly) {
  auto inner = std::make_unique<CountingReader>(100000, false);
  const CountingReader& counting = *inner;
  {
    ReadAheadLogReader reader(std::move(inner), 2);
    LogMessage message;
    for (int i = 0; i < 10; ++i) ASSERT_TRUE(reader.next(message));
    EXPECT_LT(reader.stats().imu_samples + reader.stats().scans, 100);  // stops the thread
    EXPECT_LT(counting.read(), 100);
  }  // and the destructor returns with the thread stopped
}

}  // namespace
}  // namespace storey
