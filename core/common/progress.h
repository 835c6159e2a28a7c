#pragma once
/// Progress reporting from long-running core work to a face (terminal bar in
/// the CLI, progress dialog in the plugin), and ProgressMeter: what a face
/// shows from it (elapsed time, time left, speed), with no terminal or GUI code.
#include <functional>
#include <optional>
#include <string>

namespace storey {

/// Called with the fraction done in [0, 1] and the current stage's name.
/// Returns false to ask the work to stop; the callee then throws storey::Cancelled.
using ProgressFn = std::function<bool(double fraction, const std::string& stage)>;

/// Optional companion of a ProgressFn for work that reads a log: the log's
/// own time processed so far [s after its first message], so a face can show
/// the speed as a multiple of real time. Called on the ProgressFn's thread,
/// just before it.
using LogTimeFn = std::function<void(double log_seconds)>;

/// What a face shows about running work.
struct ProgressReading {
  std::string stage;
  double fraction = 0.0;        ///< of the current stage, in [0, 1]
  double elapsed = 0.0;         ///< since the meter started [s]
  std::optional<double> left;   ///< the current stage's time left [s], when it can be estimated
  std::optional<double> speed;  ///< log seconds per wall second, while the stage reads the log
};

/// Turns ProgressFn and LogTimeFn updates into a ProgressReading. Times are
/// seconds on any one clock: the callers without `now` use steadySeconds().
///  - time left: the current stage's elapsed time x (1 - f) / (f - f0), f0 the
///    fraction the stage started at; unknown until the stage has run 1 s and
///    moved by 1 %;
///  - speed: log time over wall time since the first log time of the stage,
///    known after 1 s; only while the current stage is the one reading the log.
class ProgressMeter {
 public:
  explicit ProgressMeter(double start = steadySeconds()) : start_(start) {}
  void update(double fraction, const std::string& stage, double now);
  void update(double fraction, const std::string& stage) {
    update(fraction, stage, steadySeconds());
  }
  void setLogTime(double log_seconds, double now);
  void setLogTime(double log_seconds) { setLogTime(log_seconds, steadySeconds()); }
  ProgressReading reading(double now) const;
  ProgressReading reading() const { return reading(steadySeconds()); }
  /// Seconds on std::chrono::steady_clock.
  static double steadySeconds();

 private:
  double start_;
  std::string stage_;
  double fraction_ = 0.0;
  double stage_start_ = 0.0, stage_start_fraction_ = 0.0;
  std::string log_stage_;  ///< stage that reported log time last
  double log_first_ = 0.0, log_first_wall_ = 0.0, log_last_ = 0.0;
};

/// "0:07", "12:34", "1:02:03".
std::string formatDuration(double seconds);
/// "0:12 elapsed, 0:18 left, 2.1x real time": "? left" when unknown, the
/// speed only when known.
std::string timingText(const ProgressReading& reading);

}  // namespace storey
