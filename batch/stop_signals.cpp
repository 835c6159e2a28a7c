#include "stop_signals.h"

namespace storey::cli {
namespace {

std::atomic<bool> g_stop{false};  // written by the handler (lock-free)
std::atomic<int> g_signal{0};

extern "C" void onStopSignal(int signal_number) {
  g_signal = signal_number;
  g_stop = true;
}

}  // namespace

StopSignals::StopSignals() {
  clear();
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &old_int_);
  sigaction(SIGTERM, &action, &old_term_);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

const std::atomic<bool>& StopSignals::flag() {
  return g_stop;
}

int StopSignals::signalNumber() {
  return g_signal.load();
}

void StopSignals::clear() {
  g_stop = false;
  g_signal = 0;
}

const char* StopSignals::signalName() {
  return g_signal.load() == SIGTERM ? "SIGTERM" : "Ctrl-C (SIGINT)";
}

}  // namespace storey::cli
