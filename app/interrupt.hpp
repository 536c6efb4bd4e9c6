// Ctrl-C in `nsbridge run` and `nsbridge sweep`: the first SIGINT sets a stop request that
// the runs read at every progress report (integrators::RunHooks::stop); a run so stopped is
// interrupted and writes nothing, and the command exits with kInterruptedExit. A second
// SIGINT ends the process at once, as SIGINT does by default. A process started with SIGINT
// ignored (nohup, a background job of a script) keeps it ignored.
#pragma once

#include <atomic>

namespace nsb::app {

// The shell's code for a process ended by SIGINT: 128 + 2.
inline constexpr int kInterruptedExit = 130;

// Installs the SIGINT handler (once) and returns the stop request it sets.
std::atomic<bool>& stop_on_interrupt();

}  // namespace nsb::app
