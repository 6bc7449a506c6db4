#include "apps/stop_signals.h"

#include <signal.h>

namespace adahrs::apps {
namespace {

std::atomic<bool> g_stop_requested{false};
std::atomic<int> g_stop_signal{0};

extern "C" void OnStopSignal(int signal_number) {
  g_stop_signal = signal_number;
  g_stop_requested = true;
}

}  // namespace

const std::atomic<bool>& InstallStopSignals() {
  struct sigaction action {};
  action.sa_handler = OnStopSignal;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal_number, &action, nullptr);
  return g_stop_requested;
}

int StopSignal() {
  const int signal_number = g_stop_signal.load();
  return signal_number != 0 ? signal_number : SIGINT;
}

const char* StopSignalName() {
  switch (StopSignal()) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

int StopExitStatus() { return 128 + StopSignal(); }

}  // namespace adahrs::apps
