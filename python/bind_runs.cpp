// nsbridge.load_scene, Scene, run and Result: the run pipeline (runs/run.hpp) from Python.
// A run is runs::prepare then runs::run, exactly as `nsbridge run` does it; its outputs are
// the record's, converted once: summary.json's text parsed by Python's json module, each
// history column copied into one numpy array (docs/python.md).
#include "integrators/run.hpp"
#include "io/csv.hpp"
#include "io/files.hpp"
#include "python/bindings.hpp"
#include "python/progress.hpp"
#include "runs/files.hpp"
#include "runs/run.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace nsb::python {

namespace {

// A scene file with its overrides, loaded and checked once (runs::prepare): what it says is
// kept, the system is not. run() loads it again from the same file and overrides, since a
// run consumes its system.
struct Scene {
  std::filesystem::path path;
  std::vector<std::string> overrides;
  std::string name, kind, method;
  double end_time = 0.0;               // [s]
  std::vector<std::string> warnings;   // the step warnings found before a run (runs/trust.hpp)
};

Scene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  runs::PreparedRun p;
  {
    py::gil_scoped_release release;
    p = runs::prepare({path, overrides, {}, {}});
  }
  return Scene{path,
               overrides,
               p.scene.name,
               p.scene.kind,
               std::string(integrators::method_name(p.scene.run)),
               integrators::end_time(p.scene.run),
               std::move(p.warnings)};
}

// One run's record and, built on first use, its Python views.
class Result {
 public:
  explicit Result(runs::RunRecord record) : record_(std::move(record)) {}

  const runs::RunRecord& record() const { return record_; }

  // summary.json as a dict: its text (runs::summary_json) parsed by Python's json module, so
  // the dict and the file cannot differ.
  py::object summary() {
    if (!summary_) summary_ = py::module_::import("json").attr("loads")(runs::summary_json(record_));
    return summary_;
  }

  // history.csv's columns, each one numpy float64 array copied from the row-major samples
  // with a stride of the row width. Non-finite samples stay NaN or inf (history.csv writes
  // an empty field for them).
  py::object history() {
    if (history_) return history_;
    const integrators::Recorder& h = record_.history;
    const std::size_t rows = h.rows();
    py::dict d;
    for (std::size_t c = 0; c < h.columns().size(); ++c) {
      py::array_t<double> column(static_cast<py::ssize_t>(rows));
      double* out = column.mutable_data();
      for (std::size_t r = 0; r < rows; ++r) out[r] = h.at(r, c);
      d[py::str(h.columns()[c])] = std::move(column);
    }
    history_ = std::move(d);
    return history_;
  }

  // events.csv's columns: t [s] (float64) and contact (int64, 0 = no single contact) as numpy
  // arrays, kind and note as lists of str.
  py::object events() {
    if (events_) return events_;
    const auto& events = record_.history.events();
    const auto n = static_cast<py::ssize_t>(events.size());
    py::array_t<double> t(n);
    py::array_t<std::int64_t> contact(n);
    py::list kind(n), note(n);
    for (py::ssize_t i = 0; i < n; ++i) {
      const integrators::Event& e = events[static_cast<std::size_t>(i)];
      t.mutable_data()[i] = e.t;
      contact.mutable_data()[i] = e.contact;
      kind[i] = py::str(std::string(integrators::to_string(e.kind)));
      note[i] = py::str(e.note);
    }
    py::dict d;
    d["t"] = std::move(t);
    d["contact"] = std::move(contact);
    d["kind"] = std::move(kind);
    d["note"] = std::move(note);
    events_ = std::move(d);
    return events_;
  }

  // The files `nsbridge run --out dir` writes (runs::write_record), after the same check of
  // the folder: a place that cannot be written is bad input, as on the command line.
  void write(const std::filesystem::path& dir) const {
    py::gil_scoped_release release;
    try {
      io::prepare_output_dir(dir);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("Result.write: ") + e.what());
    }
    runs::write_record(dir, record_);
  }

 private:
  runs::RunRecord record_;
  py::object summary_, history_, events_;  // null until first asked for
};

// run(scene_or_path, method, overrides, progress): the request, then runs::prepare and
// runs::run with the GIL released, so that other Python threads run meanwhile.
Result run(const py::object& scene, const std::optional<std::string>& method,
           const std::vector<std::string>& overrides, const py::object& progress) {
  runs::RunRequest request;
  if (py::isinstance<Scene>(scene)) {
    const Scene& s = scene.cast<const Scene&>();
    request.scene = s.path;
    request.overrides = s.overrides;
  } else if (py::isinstance<py::str>(scene) || py::hasattr(scene, "__fspath__")) {
    request.scene = scene.cast<std::filesystem::path>();
  } else {
    throw py::type_error("run: scene_or_path: expected a Scene or a path");
  }
  request.overrides.insert(request.overrides.end(), overrides.begin(), overrides.end());
  request.method = method.value_or("");
  ProgressReport report(progress);
  std::optional<runs::RunRecord> record;
  {
    py::gil_scoped_release release;
    runs::PreparedRun prepared = runs::prepare(request);
    report.start(integrators::end_time(prepared.scene.run));
    record.emplace(runs::run(std::move(prepared), report.callback()));
  }
  report.finish();  // raises what a Python progress callable raised, if anything
  return Result(std::move(*record));
}

std::string scene_repr(const Scene& s) {
  return "Scene('" + s.path.string() + "', name='" + s.name + "', method='" + s.method +
         "', end_time=" + io::three_digits(s.end_time) + ")";
}

void bind_scene(py::module_& m) {
  py::class_<Scene>(m, "Scene",
                    "A scene file with its overrides, loaded and checked (nsbridge.load_scene)")
      .def_readonly("path", &Scene::path, "The scene file")
      .def_readonly("overrides", &Scene::overrides, "\"section.key=value\" overrides, in order")
      .def_readonly("name", &Scene::name, "The scene's name (the file's stem)")
      .def_readonly("kind", &Scene::kind, "[model] kind")
      .def_readonly("method", &Scene::method,
                    "solver.method: 'moreau', 'event_driven' or 'compliance'")
      .def_readonly("end_time", &Scene::end_time, "solver.end_time [s]")
      .def_readonly("warnings", &Scene::warnings, "Step warnings found before a run")
      .def("with_overrides",
           [](const Scene& s, const std::vector<std::string>& more) {
             std::vector<std::string> all = s.overrides;
             all.insert(all.end(), more.begin(), more.end());
             return load_scene(s.path, all);
           },
           py::arg("overrides"),
           "A new Scene: this one's overrides followed by these, loaded and checked")
      .def("__repr__", &scene_repr);
  m.def("load_scene", &load_scene, py::arg("path"), py::arg("overrides") = std::vector<std::string>{},
        "Loads and checks a scene file (TOML, docs/scenes.md) with \"section.key=value\" "
        "overrides; bad input raises InputError naming the file, line and key");
}

void bind_result(py::module_& m) {
  py::class_<Result>(m, "Result", "One run: its status, summary, history and events")
      .def_property_readonly("status", [](const Result& r) {
        return std::string(integrators::to_string(r.record().result.status));
      }, "summary.json's status: 'completed', 'completed_with_fallbacks', 'contact_unsolved', "
         "'diverged', 'stalled' or 'unseated'")
      .def_property_readonly("name", [](const Result& r) { return r.record().scene_name; },
                             "The scene's name")
      .def_property_readonly("method", [](const Result& r) { return r.record().result.method; },
                             "The method that ran")
      .def_property_readonly("summary", &Result::summary, "summary.json as a dict")
      .def_property_readonly(
          "limit_states",
          [](Result& r) -> py::object { return r.summary()["limit_states"]; },
          "summary.json's limit_states: {name: {exceeded, time, margin, unit}} "
          "(docs/limit-states.md); {} when the system watches none")
      .def_property_readonly("history", &Result::history,
                             "history.csv's columns: name -> numpy float64 array")
      .def_property_readonly("events", &Result::events,
                             "events.csv's columns: t, contact (numpy arrays), kind, note (lists)")
      .def("write", &Result::write, py::arg("dir"),
           "Writes history.csv, events.csv and summary.json into dir, as `nsbridge run` does")
      .def("__repr__", [](const Result& r) {
        return "Result(name='" + r.record().scene_name + "', method='" +
               r.record().result.method + "', status='" +
               std::string(integrators::to_string(r.record().result.status)) + "')";
      });
}

}  // namespace

void bind_runs(py::module_& m) {
  bind_scene(m);
  bind_result(m);
  m.def("run", &run, py::arg("scene_or_path"), py::arg("method") = py::none(),
        py::arg("overrides") = std::vector<std::string>{}, py::arg("progress") = false,
        "Runs a scene (a Scene or a path) with `nsbridge run`'s pipeline, the GIL released; "
        "method overrides solver.method; progress: False, True (a line on stderr) or a "
        "callable f(t). A numerical failure is Result.status, bad input raises InputError");
}

}  // namespace nsb::python
