#include "io/read_ahead_log_reader.h"

#include <algorithm>
#include <variant>

namespace storey {

ReadAheadLogReader::ReadAheadLogReader(std::unique_ptr<LogReader> inner, int max_scans,
                                       int max_messages)
    : inner_(std::move(inner)),
      description_(inner_->describe()),
      max_scans_(std::max(max_scans, 1)),
      max_messages_(static_cast<std::size_t>(std::max(max_messages, 1))) {}

ReadAheadLogReader::~ReadAheadLogReader() {
  stop();
}

void ReadAheadLogReader::stop() const {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void ReadAheadLogReader::read() {
  try {
    for (;;) {
      Item item;
      if (!inner_->next(item.message)) break;
      item.progress = inner_->progress();
      const bool scan = std::holds_alternative<Scan>(item.message);
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] {
        return stopping_ || (queued_scans_ < max_scans_ && queue_.size() < max_messages_);
      });
      if (stopping_) break;
      queue_.push_back(std::move(item));
      queued_scans_ += scan ? 1 : 0;
      lock.unlock();
      changed_.notify_all();
    }
  } catch (...) {
    const std::lock_guard<std::mutex> lock(mutex_);
    error_ = std::current_exception();
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  changed_.notify_all();
}

bool ReadAheadLogReader::next(LogMessage& message) {
  if (!thread_.joinable() && !done_) thread_ = std::thread([this] { read(); });
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return !queue_.empty() || done_; });
  if (queue_.empty()) {
    lock.unlock();
    if (thread_.joinable()) thread_.join();
    if (error_) {
      const std::exception_ptr error = error_;
      error_ = nullptr;
      std::rethrow_exception(error);
    }
    return false;
  }
  Item& item = queue_.front();
  message = std::move(item.message);
  progress_ = item.progress;
  queued_scans_ -= std::holds_alternative<Scan>(message) ? 1 : 0;
  queue_.pop_front();
  lock.unlock();
  changed_.notify_all();
  return true;
}

const LogReadStats& ReadAheadLogReader::stats() const {
  stop();
  return inner_->stats();
}

}  // namespace storey
