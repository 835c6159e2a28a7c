#pragma once
/// Progress of a long command on stderr: a bar redrawn in place on a
/// terminal, plain lines at 10 % steps otherwise (logs, CI).
#include <string>

#include "common/progress.h"

namespace storey::cli {

class ProgressBar {
 public:
  /// `label` prefixes the plain lines ("storey <label>: 40% stage").
  explicit ProgressBar(std::string label, bool enabled = true);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  bool update(double fraction, const std::string& stage);
  /// A ProgressFn that draws on this bar (the bar must outlive it).
  ProgressFn callback() {
    return [this](double f, const std::string& s) { return update(f, s); };
  }
  /// Ends the bar's line.
  void done();

 private:
  std::string label_;
  bool enabled_, tty_;
  bool drawn_ = false;
  int last_decile_ = -1;
  std::string last_stage_;
};

}  // namespace storey::cli
