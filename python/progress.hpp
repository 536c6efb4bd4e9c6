// What nsbridge.run(progress=...) reports while a run integrates with the GIL released:
// nothing (False), a line on sys.stderr (True: simulated time reached, speed, at most five
// times a second), or a Python callable f(t) called with the simulated time reached [s].
// The integrators call their progress callback every few thousand steps (docs/run-api.md);
// it must not throw, so an exception of the callable is kept and raised after the run.
//
// Ctrl-C: Python's SIGINT handler only sets a flag, which Python reads when it runs again, so
// a run with the GIL released would raise KeyboardInterrupt only at its end. The callback
// therefore takes the GIL at most every kSignalPoll of wall time and lets Python handle its
// signals (PyErr_CheckSignals); a KeyboardInterrupt (from there or from the callable) sets the
// run's stop request (runs::RunRequest::stop), the run ends as interrupted, and finish()
// raises it.
#pragma once

#include "integrators/recorder.hpp"

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <optional>

namespace nsb::python {

// How often a run or a sweep with the GIL released lets Python handle its signals: a tenth of
// the 0.5 s within which Ctrl-C is to raise KeyboardInterrupt, and rare enough that taking the
// GIL costs nothing measurable.
inline constexpr std::chrono::milliseconds kSignalPoll{50};

class ProgressReport {
 public:
  // progress: False, True or a callable; anything else is bad input (std::invalid_argument).
  explicit ProgressReport(const pybind11::object& progress);
  ProgressReport(const ProgressReport&) = delete;
  ProgressReport& operator=(const ProgressReport&) = delete;

  // Before the run, without the GIL: the end time [s] of the line on stderr.
  void start(double end_time);
  // The integrator's callback; valid while this object lives.
  integrators::Progress callback();
  // The stop request the callback sets on KeyboardInterrupt (runs::RunRequest::stop).
  const std::atomic<bool>* stop() const { return &stop_; }
  // After the run, with the GIL: ends the line on stderr; raises what the callable raised.
  void finish();

 private:
  void report(double t);  // called without the GIL

  pybind11::object callable_;  // None unless a callable was given
  bool line_ = false;          // progress=True
  bool drawn_ = false;
  double end_time_ = 0.0;
  double last_ = -1.0;         // wall time of the last line [s]
  double last_poll_ = -1.0;    // wall time of the last PyErr_CheckSignals [s]
  std::atomic<bool> stop_{false};
  std::chrono::steady_clock::time_point start_;
  std::optional<pybind11::error_already_set> error_;
};

}  // namespace nsb::python
