#include "app/interrupt.hpp"

#include <csignal>

namespace nsb::app {

namespace {

// A lock-free atomic is what a signal handler may touch besides volatile sig_atomic_t.
std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_interrupt(int) {
  if (g_stop.exchange(true)) {
    // The second Ctrl-C: the default action, which ends the process now.
    std::signal(SIGINT, SIG_DFL);
    std::raise(SIGINT);
  }
}

}  // namespace

std::atomic<bool>& stop_on_interrupt() {
  static const bool installed = [] {
    // A SIGINT ignored by whoever started the process (nohup, a background job of a script)
    // stays ignored, as the shell's convention asks.
    struct sigaction inherited {};
    if (sigaction(SIGINT, nullptr, &inherited) == 0 && inherited.sa_handler == SIG_IGN)
      return false;
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;  // reads and writes go on; the runs poll the request
    sigaction(SIGINT, &action, nullptr);
    return true;
  }();
  (void)installed;
  return g_stop;
}

}  // namespace nsb::app
