#pragma once
/// Minimal logging sink for core: messages go to a replaceable function so the
/// CLI prints them to stderr (above its progress bar) and the plugin to
/// CloudCompare's console. A LogRecorder keeps a run's warnings for its report.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace storey {

enum class LogLevel { kDebug, kInfo, kWarning, kError };

using LogSink = std::function<void(LogLevel, const std::string&)>;

/// Replaces the process-wide sink (default: "[level] message" on stderr,
/// debug suppressed; null: messages are dropped). Not thread-safe against
/// concurrent logging: set it once at start-up.
void setLogSink(LogSink sink);
/// The default sink's text of a message: "[info] message", "[warning] message", ...
std::string formatLogLine(LogLevel level, const std::string& message);
void logMessage(LogLevel level, const std::string& message);
inline void logInfo(const std::string& m) {
  logMessage(LogLevel::kInfo, m);
}
inline void logWarning(const std::string& m) {
  logMessage(LogLevel::kWarning, m);
}
inline void logDebug(const std::string& m) {
  logMessage(LogLevel::kDebug, m);
}

/// While it lives, keeps the warnings and errors logged anywhere in the
/// process (from any thread), besides the sink printing them: a run's
/// warnings for its report. Two recorders alive at once both see every message.
class LogRecorder {
 public:
  static constexpr std::size_t kMaxKept = 100;  ///< messages kept; all are counted

  LogRecorder();
  ~LogRecorder();
  LogRecorder(const LogRecorder&) = delete;
  LogRecorder& operator=(const LogRecorder&) = delete;

  /// The first kMaxKept warning and error messages, in order.
  std::vector<std::string> warnings() const;
  /// Warnings and errors logged so far (kept or not).
  std::size_t warningCount() const;

 private:
  friend void logMessage(LogLevel, const std::string&);
  std::vector<std::string> kept_;
  std::size_t count_ = 0;
};

}  // namespace storey
