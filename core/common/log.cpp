#include "common/log.h"

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
    const char* tag = level == LogLevel::kInfo      ? "info"
                      : level == LogLevel::kWarning ? "warning"
                                                    : "error";
    std::cerr << "[" << tag << "] " << message << '\n';
  };
  return s;
}

}  // namespace

void setLogSink(LogSink new_sink) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  sink() = std::move(new_sink);
}

void logMessage(LogLevel level, const std::string& message) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  if (sink()) sink()(level, message);
}

}  // namespace storey
