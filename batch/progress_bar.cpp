#include "progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <iomanip>
#include <iostream>

namespace storey::cli {

ProgressBar::ProgressBar(std::string label, bool enabled)
    : label_(std::move(label)), enabled_(enabled), tty_(::isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() { done(); }

bool ProgressBar::update(double fraction, const std::string& stage) {
  if (!enabled_) return true;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const int percent = static_cast<int>(fraction * 100.0);
  if (tty_) {
    constexpr int kWidth = 40;
    const int filled = static_cast<int>(fraction * kWidth);
    std::cerr << "\r[" << std::string(filled, '#') << std::string(kWidth - filled, ' ') << "] "
              << std::setw(3) << percent << "% " << std::left << std::setw(20) << stage
              << std::right << std::flush;
    drawn_ = true;
  } else if (percent / 10 != last_decile_ || stage != last_stage_) {
    std::cerr << "storey " << label_ << ": " << percent << "% " << stage << '\n';
    last_decile_ = percent / 10;
    last_stage_ = stage;
  }
  return true;
}

void ProgressBar::done() {
  if (drawn_) std::cerr << '\n';
  drawn_ = false;
}

}  // namespace storey::cli
