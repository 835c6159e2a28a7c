#include "common/log.h"

#include <algorithm>
#include <iostream>
#include <mutex>

namespace storey {
namespace {

std::mutex& sinkMutex() {
  static std::mutex m;
  return m;
}

LogSink& sink() {
  static LogSink s = [](LogLevel level, const std::string& message) {
    if (level == LogLevel::kDebug) return;
    std::cerr << formatLogLine(level, message) << '\n';
  };
  return s;
}

/// The recorders alive (guarded by sinkMutex).
std::vector<LogRecorder*>& recorders() {
  static std::vector<LogRecorder*> r;
  return r;
}

}  // namespace

std::string formatLogLine(LogLevel level, const std::string& message) {
  const char* tag = level == LogLevel::kDebug     ? "debug"
                    : level == LogLevel::kInfo    ? "info"
                    : level == LogLevel::kWarning ? "warning"
                                                  : "error";
  return std::string("[") + tag + "] " + message;
}

void setLogSink(LogSink new_sink) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  sink() = std::move(new_sink);
}

void logMessage(LogLevel level, const std::string& message) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  if (level >= LogLevel::kWarning) {
    for (LogRecorder* r : recorders()) {
      ++r->count_;
      if (r->kept_.size() < LogRecorder::kMaxKept) r->kept_.push_back(message);
    }
  }
  if (sink()) sink()(level, message);
}

LogRecorder::LogRecorder() {
  std::lock_guard<std::mutex> lock(sinkMutex());
  recorders().push_back(this);
}

LogRecorder::~LogRecorder() {
  std::lock_guard<std::mutex> lock(sinkMutex());
  auto& r = recorders();
  r.erase(std::remove(r.begin(), r.end(), this), r.end());
}

std::vector<std::string> LogRecorder::warnings() const {
  std::lock_guard<std::mutex> lock(sinkMutex());
  return kept_;
}

std::size_t LogRecorder::warningCount() const {
  std::lock_guard<std::mutex> lock(sinkMutex());
  return count_;
}

}  // namespace storey
