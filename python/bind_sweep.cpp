// nsbridge.sweep, build_info and __version__: a sweep (sweep/runner.hpp) as `nsbridge sweep`
// runs it, and what the module was built from (io/build_info.hpp).
#include "io/build_info.hpp"
#include "python/bindings.hpp"
#include "python/progress.hpp"
#include "sweep/runner.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <future>
#include <thread>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;

namespace nsb::python {

namespace {

// One column of a sweep's results, typed as its Column says (sweep/results.hpp): a tuple
// (name, kind, values, missing) with kind "real" (float64, NaN where missing), "integer"
// (int64) or "boolean" (bool), each with `missing` a bool array marking the absent values (a
// rejected run's counts, a limit state a run does not have), or "text" (a list of str).
py::tuple column(const sweep::Results& results, std::size_t c) {
  const sweep::Column& col = results.columns[c];
  const auto n = static_cast<py::ssize_t>(results.rows.size());
  py::array_t<bool> missing(n);
  bool* absent = missing.mutable_data();
  const auto typed = [&](auto* out, auto cast) {
    for (py::ssize_t r = 0; r < n; ++r) {
      const std::optional<double> v = results.number(results.rows[static_cast<std::size_t>(r)], c);
      absent[r] = !v;
      out[r] = v ? cast(*v) : decltype(cast(0.0)){};
    }
  };
  py::object values;
  switch (col.kind) {
    case sweep::ValueKind::kReal: {
      py::array_t<double> a(n);
      typed(a.mutable_data(), [](double v) { return v; });
      // A value that is not finite, or absent, is NaN (an empty field of results.csv).
      for (py::ssize_t r = 0; r < n; ++r)
        if (absent[r]) a.mutable_data()[r] = std::numeric_limits<double>::quiet_NaN();
      values = a;
      break;
    }
    case sweep::ValueKind::kInteger: {
      py::array_t<std::int64_t> a(n);
      typed(a.mutable_data(), [](double v) { return static_cast<std::int64_t>(v); });
      values = a;
      break;
    }
    case sweep::ValueKind::kBoolean: {
      py::array_t<bool> a(n);
      // A factor level "true"/"false", or a limit state's exceeded (1/0).
      for (py::ssize_t r = 0; r < n; ++r) {
        const sweep::Row& row = results.rows[static_cast<std::size_t>(r)];
        const std::string cell = results.cell(row, c);
        absent[r] = cell.empty();
        a.mutable_data()[r] = cell == "1" || cell == "true";
      }
      values = a;
      break;
    }
    case sweep::ValueKind::kText: {
      py::list text;
      for (const auto& row : results.rows) text.append(py::str(results.cell(row, c)));
      for (py::ssize_t r = 0; r < n; ++r) absent[r] = false;
      values = text;
      break;
    }
  }
  return py::make_tuple(col.name, std::string(sweep::to_string(col.kind)), values, missing);
}

// Runs a sweep as `nsbridge sweep design --out out --jobs jobs --set ... [--restart]` does (no
// progress bar, no plot), the GIL released, and returns its typed columns (column()), in the
// order of results.csv. The sweep runs on a thread of its own while this one, every
// kSignalPoll, lets Python handle its signals: a KeyboardInterrupt sets the sweep's stop
// request (the runs under way end as interrupted and write nothing), and is raised once the
// sweep has stopped; a rerun resumes it.
py::list run_sweep(const std::filesystem::path& design, const std::filesystem::path& out,
                   const std::optional<int>& jobs, const std::vector<std::string>& overrides,
                   bool restart) {
  sweep::SweepOptions options;
  options.out = out;
  options.jobs = jobs.value_or(0);
  options.restart = restart;
  options.progress = false;
  options.set = overrides;
  std::atomic<bool> stop{false};
  options.stop = &stop;
  sweep::Results results;
  std::exception_ptr failure;
  std::optional<py::error_already_set> interrupt;
  {
    py::gil_scoped_release release;
    std::promise<void> done;
    std::future<void> finished = done.get_future();
    std::thread worker([&] {
      try {
        results = sweep::run_sweep(design, options).table;
      } catch (...) {
        failure = std::current_exception();
      }
      done.set_value();
    });
    while (finished.wait_for(kSignalPoll) != std::future_status::ready) {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        interrupt.emplace();  // the KeyboardInterrupt the SIGINT handler raised
        stop.store(true);
        break;
      }
    }
    worker.join();
  }
  if (interrupt) throw std::move(*interrupt);
  if (failure) std::rethrow_exception(failure);
  py::list columns;
  for (std::size_t c = 0; c < results.columns.size(); ++c) columns.append(column(results, c));
  return columns;
}

py::dict build_info() {
  const io::BuildInfo& b = io::build_info();
  py::dict libraries;
  for (const auto& [name, version] : b.libraries) libraries[py::str(name)] = version;
  libraries["pybind11"] = std::to_string(PYBIND11_VERSION_MAJOR) + "." +
                          std::to_string(PYBIND11_VERSION_MINOR) + "." +
                          std::to_string(PYBIND11_VERSION_PATCH);
  libraries["Python"] = PY_VERSION;  // the headers the module was compiled against
  py::dict d;
  d["version"] = b.version;
  d["revision"] = b.revision;
  d["build_type"] = b.build_type;
  d["compiler"] = b.compiler;
  d["libraries"] = libraries;
  return d;
}

}  // namespace

void bind_sweep(py::module_& m) {
  m.attr("__version__") = io::build_info().version;
  m.def("build_info", &build_info,
        "What the module was built from: version, revision (git, at build time), build_type, "
        "compiler and libraries (name -> version), as `nsbridge --version` says");
  m.def("_sweep_columns", &run_sweep, py::arg("design_path"), py::arg("out"),
        py::arg("jobs") = py::none(), py::arg("overrides") = std::vector<std::string>{},
        py::arg("restart") = false,
        "Runs a sweep design as nsbridge.sweep does; returns its columns as tuples (name, kind, "
        "values, missing), kind one of real, integer, boolean, text");
}

}  // namespace nsb::python
