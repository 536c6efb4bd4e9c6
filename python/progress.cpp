#include "python/progress.hpp"

#include <cstdio>
#include <stdexcept>
#include <utility>

namespace py = pybind11;

namespace nsb::python {

ProgressReport::ProgressReport(const py::object& progress) {
  if (py::isinstance<py::bool_>(progress)) {
    line_ = progress.cast<bool>();
  } else if (PyCallable_Check(progress.ptr()) != 0) {
    callable_ = progress;
  } else if (!progress.is_none()) {
    throw std::invalid_argument("run: progress: expected False, True or a callable f(t)");
  }
}

void ProgressReport::start(double end_time) {
  end_time_ = end_time;
  start_ = std::chrono::steady_clock::now();
}

integrators::Progress ProgressReport::callback() {
  return [this](double t) { report(t); };
}

void ProgressReport::report(double t) {
  if (error_) return;  // the callable (or sys.stderr) raised: nothing more is reported
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const bool poll = wall - last_poll_ >= std::chrono::duration<double>(kSignalPoll).count();
  char text[96] = "";
  bool draw = false;
  if (line_ && (wall - last_ >= 0.2 || t >= end_time_)) {
    // The line: at most every 0.2 s of wall time, and always at the end.
    last_ = wall;
    draw = true;
    std::snprintf(text, sizeof text, "\rnsbridge: t = %.4g / %.4g s  %.3g x real time ", t,
                  end_time_, wall > 0.0 ? t / wall : 0.0);
  }
  if (!poll && !draw && !callable_) return;
  py::gil_scoped_acquire acquire;
  if (poll) {
    last_poll_ = wall;
    if (PyErr_CheckSignals() != 0) {
      error_.emplace();  // the KeyboardInterrupt the SIGINT handler raised
      stop_.store(true);
      return;
    }
  }
  try {
    if (callable_) {
      callable_(t);
    } else if (draw) {
      py::module_::import("sys").attr("stderr").attr("write")(text);
      drawn_ = true;
    }
  } catch (py::error_already_set& e) {
    if (e.matches(PyExc_KeyboardInterrupt)) stop_.store(true);
    error_.emplace(std::move(e));
  }
}

void ProgressReport::finish() {
  if (drawn_) py::module_::import("sys").attr("stderr").attr("write")("\n");
  drawn_ = false;
  if (error_) {
    py::error_already_set e = std::move(*error_);
    error_.reset();
    throw e;
  }
}

}  // namespace nsb::python
