// nsbridge.sweep, build_info and __version__: a sweep (sweep/runner.hpp) as `nsbridge sweep`
// runs it, and what the module was built from (io/build_info.hpp).
#include "io/build_info.hpp"
#include "python/bindings.hpp"
#include "sweep/csv.hpp"
#include "sweep/runner.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;

namespace nsb::python {

namespace {

// A results.csv field as a number: the whole field parsed, or an empty field (a value that
// was not finite, io::csv_number) as NaN; std::nullopt for text.
std::optional<double> number(const std::string& field) {
  if (field.empty()) return std::numeric_limits<double>::quiet_NaN();
  double v = 0.0;
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, v);
  if (ec != std::errc{} || ptr != end) return std::nullopt;
  return v;
}

// The columns of results.csv that hold text whatever their fields look like: the run id
// ("0007"), the status and the message (docs/sweep.md).
bool text_column(const std::string& name) {
  return name == "run" || name == "status" || name == "message";
}

// One column of a table: a numpy float64 array when every field is a number, else a list of
// str (the text columns, a factor's level names).
py::object column(const sweep::Table& table, std::size_t c) {
  const std::size_t n = table.rows.size();
  const bool is_text = text_column(table.header[c]);
  py::array_t<double> values(static_cast<py::ssize_t>(n));
  double* out = values.mutable_data();
  for (std::size_t r = 0; r < n; ++r) {
    const std::optional<double> v = is_text ? std::nullopt : number(table.rows[r][c]);
    if (!v) {
      py::list text;
      for (const auto& row : table.rows) text.append(py::str(row[c]));
      return text;
    }
    out[r] = *v;
  }
  return values;
}

// Runs a sweep as `nsbridge sweep design --out out --jobs jobs --set ... [--restart]` does (no
// progress bar, no plot), the GIL released, and returns the columns of its results.csv.
py::dict run_sweep(const std::filesystem::path& design, const std::filesystem::path& out,
                   const std::optional<int>& jobs, const std::vector<std::string>& overrides,
                   bool restart) {
  sweep::SweepOptions options;
  options.out = out;
  options.jobs = jobs.value_or(0);
  options.restart = restart;
  options.progress = false;
  options.set = overrides;
  sweep::Table table;
  {
    py::gil_scoped_release release;
    const sweep::SweepSummary summary = sweep::run_sweep(design, options);
    table = sweep::read_csv(summary.results);
  }
  py::dict d;
  for (std::size_t c = 0; c < table.header.size(); ++c) d[py::str(table.header[c])] = column(table, c);
  return d;
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
  m.def("sweep", &run_sweep, py::arg("design_path"), py::arg("out"), py::arg("jobs") = py::none(),
        py::arg("overrides") = std::vector<std::string>{}, py::arg("restart") = false,
        "Runs a sweep design (docs/sweep.md) into the folder out, as `nsbridge sweep` does "
        "(runs already complete there are kept; a folder of another design is refused unless "
        "restart), on jobs threads (None: all cores), the GIL released; returns results.csv's columns: numpy float64 arrays for numeric columns, "
        "lists of str otherwise");
}

}  // namespace nsb::python
