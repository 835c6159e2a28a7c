#pragma once
/// Ctrl-C (SIGINT) and SIGTERM as a request to stop: while a StopSignals
/// lives, they set a flag the command polls instead of killing the process,
/// so it can stop cleanly (cancel its children, leave no partial output) and
/// say so. The previous handlers come back when it is destroyed.
#include <signal.h>

#include <atomic>

namespace storey::cli {

class StopSignals {
 public:
  StopSignals();  ///< clears the flag and installs the handlers
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// Set by the handler when a signal arrived (until clear()).
  static const std::atomic<bool>& flag();
  static bool requested() { return flag().load(); }
  /// The signal that arrived last (SIGINT or SIGTERM), 0 if none.
  static int signalNumber();
  static void clear();
  /// "Ctrl-C (SIGINT)" or "SIGTERM".
  static const char* signalName();

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace storey::cli
