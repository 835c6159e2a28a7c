#include "common/progress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace storey {

namespace {
constexpr double kMinStageSeconds = 1.0;  ///< before it, no time left is estimated
constexpr double kMinStageFraction = 0.01;
constexpr double kMinLogSeconds = 1.0;  ///< wall time before a speed is shown
}  // namespace

double ProgressMeter::steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void ProgressMeter::update(double fraction, const std::string& stage, double now) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  // A new stage, or the same one starting over, restarts the stage's clock.
  if (stage != stage_ || fraction < fraction_) {
    stage_ = stage;
    stage_start_ = now;
    stage_start_fraction_ = fraction;
  }
  fraction_ = fraction;
}

void ProgressMeter::setLogTime(double log_seconds, double now) {
  if (log_stage_ != stage_ || log_seconds < log_last_) {
    log_stage_ = stage_;
    log_first_ = log_seconds;
    log_first_wall_ = now;
  }
  log_last_ = log_seconds;
}

ProgressReading ProgressMeter::reading(double now) const {
  ProgressReading r;
  r.stage = stage_;
  r.fraction = fraction_;
  r.elapsed = std::max(0.0, now - start_);
  const double stage_seconds = now - stage_start_;
  const double moved = fraction_ - stage_start_fraction_;
  if (fraction_ >= 1.0 && moved > 0.0) {
    r.left = 0.0;
  } else if (stage_seconds >= kMinStageSeconds && moved >= kMinStageFraction) {
    r.left = stage_seconds * (1.0 - fraction_) / moved;
  }
  const double log_wall = now - log_first_wall_;
  if (!log_stage_.empty() && log_stage_ == stage_ && log_wall >= kMinLogSeconds)
    r.speed = (log_last_ - log_first_) / log_wall;
  return r;
}

std::string formatDuration(double seconds) {
  const long total = std::lround(std::max(0.0, seconds));
  char text[32];
  if (total >= 3600)
    std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  else
    std::snprintf(text, sizeof(text), "%ld:%02ld", total / 60, total % 60);
  return text;
}

std::string timingText(const ProgressReading& r) {
  std::string text = formatDuration(r.elapsed) + " elapsed, " +
                     (r.left ? formatDuration(*r.left) : std::string("?")) + " left";
  if (r.speed) {
    char speed[48];
    std::snprintf(speed, sizeof(speed), ", %.1fx real time", *r.speed);
    text += speed;
  }
  return text;
}

}  // namespace storey
