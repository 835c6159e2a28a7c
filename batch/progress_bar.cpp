#include "progress_bar.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>

#include "common/log.h"

namespace storey::cli {

namespace {

constexpr int kBarWidth = 24;
constexpr double kHeartbeatSeconds = 30.0;  ///< plain lines: at least one this often

/// The bar log messages are printed above (null: none shown).
std::mutex& activeMutex() {
  static std::mutex m;
  return m;
}
ProgressBar*& active() {
  static ProgressBar* bar = nullptr;
  return bar;
}

bool stderrIsTerminal() {
  const char* term = std::getenv("TERM");
  return ::isatty(STDERR_FILENO) == 1 && !(term != nullptr && std::string(term) == "dumb");
}

/// Columns of the terminal on stderr (80 when unknown).
std::size_t terminalWidth() {
  winsize size{};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

int percentOf(double fraction) {
  return static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100.0);
}

}  // namespace

ProgressBar::ProgressBar(std::string label, bool enabled)
    : ProgressBar(std::move(label),
                  !enabled             ? Mode::kOff
                  : stderrIsTerminal() ? Mode::kBar
                                       : Mode::kLines,
                  std::cerr, nullptr) {}

ProgressBar::ProgressBar(std::string label, Mode mode, std::ostream& out,
                         std::function<double()> clock)
    : label_(std::move(label)),
      mode_(mode),
      out_(out),
      clock_(clock ? std::move(clock) : [] { return ProgressMeter::steadySeconds(); }),
      meter_(clock_()) {
  last_line_ = clock_();
  if (mode_ == Mode::kOff) return;
  {
    std::lock_guard<std::mutex> lock(activeMutex());
    active() = this;
  }
  if (!clock) ticker_ = std::thread([this] { tick(); });
}

ProgressBar::~ProgressBar() {
  done();
}

bool ProgressBar::update(double fraction, const std::string& stage) {
  if (mode_ == Mode::kOff) return true;
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return true;
  const double now = clock_();
  meter_.update(fraction, stage, now);
  const int percent = percentOf(fraction);
  const bool new_detail = detail_ != shown_detail_;
  if (mode_ == Mode::kBar) {
    if (stage != last_stage_ || percent != last_percent_ || new_detail) draw();
  } else if (stage != last_stage_ || percent / 10 != last_decile_ || new_detail ||
             now - last_line_ >= kHeartbeatSeconds) {
    line(now);
  }
  shown_detail_ = detail_;
  last_stage_ = stage;
  last_percent_ = percent;
  return true;
}

void ProgressBar::setLogTime(double log_seconds) {
  if (mode_ == Mode::kOff) return;
  std::lock_guard<std::mutex> lock(mutex_);
  meter_.setLogTime(log_seconds, clock_());
}

void ProgressBar::setDetail(const std::string& detail) {
  if (mode_ == Mode::kOff) return;
  std::lock_guard<std::mutex> lock(mutex_);
  detail_ = detail;  // shown by the next update()
}

void ProgressBar::print(const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) out_ << "\r\033[K";
  out_ << text << '\n';
  if (drawn_) draw();
  out_ << std::flush;
}

void ProgressBar::done() {
  {
    std::lock_guard<std::mutex> lock(activeMutex());
    if (active() == this) active() = nullptr;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finished_ = true;
    if (drawn_) {
      draw();
      out_ << '\n' << std::flush;
    }
    drawn_ = false;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
}

void ProgressBar::draw() {
  const ProgressReading r = meter_.reading(clock_());
  const int filled = static_cast<int>(std::clamp(r.fraction, 0.0, 1.0) * kBarWidth);
  std::string text = "[" + std::string(filled, '#') + std::string(kBarWidth - filled, ' ') + "] ";
  const std::string percent = std::to_string(percentOf(r.fraction));
  text += std::string(3 - std::min<std::size_t>(3, percent.size()), ' ') + percent + "% " +
          r.stage + (detail_.empty() ? "" : " " + detail_) + "  " + timingText(r);
  // Longer than the terminal's width it would wrap and '\r' would not redraw it.
  const std::size_t width = terminalWidth();
  if (text.size() >= width) text.resize(width - 1);
  out_ << "\r\033[K" << text << std::flush;
  drawn_ = true;
}

void ProgressBar::line(double now) {
  const ProgressReading r = meter_.reading(now);
  out_ << "storey " << label_ << ": " << r.stage << (detail_.empty() ? "" : " " + detail_) << ' '
       << percentOf(r.fraction) << "% (" << timingText(r) << ")\n"
       << std::flush;
  last_decile_ = percentOf(r.fraction) / 10;
  last_line_ = now;
}

void ProgressBar::tick() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!finished_) {
    wake_.wait_for(lock, std::chrono::seconds(1));
    if (finished_ || last_stage_.empty()) continue;
    if (mode_ == Mode::kBar) {
      draw();
    } else if (clock_() - last_line_ >= kHeartbeatSeconds) {
      line(clock_());
    }
  }
}

void installLogSink() {
  setLogSink([](LogLevel level, const std::string& message) {
    if (level == LogLevel::kDebug) return;
    const std::string text = formatLogLine(level, message);
    std::lock_guard<std::mutex> lock(activeMutex());
    if (active() != nullptr)
      active()->print(text);
    else
      std::cerr << text << '\n';
  });
}

}  // namespace storey::cli
