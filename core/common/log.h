#pragma once
/// Minimal logging sink for core: messages go to a replaceable function so the
/// CLI prints them to stderr and the plugin to CloudCompare's console.
#include <functional>
#include <string>

namespace storey {

enum class LogLevel { kDebug, kInfo, kWarning, kError };

using LogSink = std::function<void(LogLevel, const std::string&)>;

/// Replaces the process-wide sink (default: "[level] message" on stderr,
/// debug suppressed). Not thread-safe against concurrent logging: set it once at start-up.
void setLogSink(LogSink sink);
void logMessage(LogLevel level, const std::string& message);
inline void logInfo(const std::string& m) { logMessage(LogLevel::kInfo, m); }
inline void logWarning(const std::string& m) { logMessage(LogLevel::kWarning, m); }
inline void logDebug(const std::string& m) { logMessage(LogLevel::kDebug, m); }

}  // namespace storey
