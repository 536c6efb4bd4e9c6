// What nsbridge.run(progress=...) reports while a run integrates with the GIL released:
// nothing (False), a line on sys.stderr (True: simulated time reached, speed, at most five
// times a second), or a Python callable f(t) called with the simulated time reached [s].
// The integrators call their progress callback every few thousand steps (docs/run-api.md);
// it must not throw, so an exception of the callable is kept and raised after the run.
#pragma once

#include "integrators/recorder.hpp"

#include <pybind11/pybind11.h>

#include <chrono>
#include <optional>

namespace nsb::python {

class ProgressReport {
 public:
  // progress: False, True or a callable; anything else is bad input (std::invalid_argument).
  explicit ProgressReport(const pybind11::object& progress);
  ProgressReport(const ProgressReport&) = delete;
  ProgressReport& operator=(const ProgressReport&) = delete;

  // Before the run, without the GIL: the end time [s] of the line on stderr.
  void start(double end_time);
  // The integrator's callback (empty for False); valid while this object lives.
  integrators::Progress callback();
  // After the run, with the GIL: ends the line on stderr; raises what the callable raised.
  void finish();

 private:
  void report(double t);  // called without the GIL

  pybind11::object callable_;  // None unless a callable was given
  bool line_ = false;          // progress=True
  bool drawn_ = false;
  double end_time_ = 0.0;
  double last_ = -1.0;         // wall time of the last line [s]
  std::chrono::steady_clock::time_point start_;
  std::optional<pybind11::error_already_set> error_;
};

}  // namespace nsb::python
