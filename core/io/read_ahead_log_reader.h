#pragma once
/// Reads a log on a thread of its own, a few scans ahead of the consumer:
/// while the odometry registers one scan, the next ones are read from disk,
/// decompressed, decoded and checked (the inner reader's whole work). The
/// messages come out in the inner reader's order, unchanged, so a run gives
/// the same results with and without it (docs/benchmarks.md, issue 23).
/// An error of the inner reader comes out of next() after the messages read
/// before it, as it would without the thread.
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "io/log_reader.h"

namespace storey {

class ReadAheadLogReader : public LogReader {
 public:
  /// Holds at most `max_scans` scans (>= 1) and `max_messages` messages
  /// (>= 1) read ahead. The thread starts with the first next().
  ReadAheadLogReader(std::unique_ptr<LogReader> inner, int max_scans, int max_messages = 8192);
  /// Stops the reading thread (a consumer may give up before the end).
  ~ReadAheadLogReader() override;

  bool next(LogMessage& message) override;
  /// The inner reader's counts; when read before next() returned false the
  /// reading thread is stopped first (they then count what it read ahead).
  const LogReadStats& stats() const override;
  /// The inner reader's description (read before the thread starts).
  std::string describe() const override { return description_; }
  /// The inner reader's progress at the message last returned.
  double progress() const override { return progress_; }

 private:
  struct Item {
    LogMessage message;
    double progress = -1.0;
  };
  void read();
  void stop() const;

  std::unique_ptr<LogReader> inner_;
  std::string description_;
  int max_scans_;
  std::size_t max_messages_;
  double progress_ = -1.0;

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::deque<Item> queue_;
  int queued_scans_ = 0;
  bool done_ = false;              ///< the thread has read its last message (or failed)
  mutable bool stopping_ = false;  ///< the consumer asks the thread to end
  std::exception_ptr error_;       ///< what ended the thread, if it failed
  mutable std::thread thread_;
};

}  // namespace storey
