#pragma once
/// Progress of a long command on stderr, with the core's log messages.
/// On a terminal: a bar redrawn in place (stage, percent, elapsed, time left,
/// speed as a multiple of real time), log messages printed above it.
/// Otherwise (a file or a pipe: CI, Slurm logs): plain lines
/// "storey <label>: <stage> <percent>% (<timing>)" at each new stage, each
/// 10 % step and every 30 s, log messages as their own lines.
#include <condition_variable>
#include <functional>
#include <iosfwd>
#include <mutex>
#include <string>
#include <thread>

#include "common/progress.h"

namespace storey::cli {

class ProgressBar {
 public:
  enum class Mode { kOff, kLines, kBar };

  /// kBar when stderr is a terminal (and TERM is not "dumb"), else kLines;
  /// kOff when not `enabled`. `label` names the command ("run", "render").
  explicit ProgressBar(std::string label, bool enabled = true);
  /// For tests: the mode, the stream and the clock [s] given; no redraws
  /// between updates (the real clock's bar redraws every second).
  ProgressBar(std::string label, Mode mode, std::ostream& out, std::function<double()> clock);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  bool update(double fraction, const std::string& stage);
  void setLogTime(double log_seconds);
  /// Text shown after the stage's name from the next update() on (e.g. the
  /// counts of a batch's logs); it does not reset the stage's time-left
  /// estimate. Plain lines: a line at each update() that changes it.
  void setDetail(const std::string& detail);
  /// A ProgressFn / LogTimeFn that draws on this bar (the bar must outlive them).
  ProgressFn callback() {
    return [this](double f, const std::string& s) { return update(f, s); };
  }
  LogTimeFn logTimeCallback() {
    return [this](double t) { setLogTime(t); };
  }
  /// A line of text (a log message) above the bar, which is redrawn below it.
  void print(const std::string& line);
  /// Ends the bar's line (the last state stays on screen); later log
  /// messages go straight to stderr.
  void done();

 private:
  void draw();            // the bar, in place (mutex_ held)
  void tick();            // every second: redraw, or a line after 30 s without one
  void line(double now);  // one plain progress line (mutex_ held)

  std::string label_;
  Mode mode_;
  std::ostream& out_;
  std::function<double()> clock_;
  std::mutex mutex_;
  ProgressMeter meter_;
  bool drawn_ = false;
  bool finished_ = false;
  int last_decile_ = -1;
  std::string last_stage_;
  std::string detail_;
  std::string shown_detail_;  ///< the detail of the last update()
  int last_percent_ = -1;
  double last_line_ = 0.0;
  std::condition_variable wake_;
  std::thread ticker_;
};

/// Routes the core's log messages (common/log.h) through the bar being
/// shown, if any, else straight to stderr. Called once at start-up.
void installLogSink();

}  // namespace storey::cli
