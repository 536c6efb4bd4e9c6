// nsbridge.load_scene, Scene, run and Result: the run pipeline (runs/run.hpp) from Python.
// A run is runs::prepare then runs::run, exactly as `nsbridge run` does it; its inputs are
// converted once (a dict to a scene table, Python values to typed overrides), its outputs are
// the record's, converted once: summary.json's text parsed by Python's json module, each
// history column copied into one numpy array (docs/python.md).
#include "integrators/run.hpp"
#include "io/csv.hpp"
#include "io/files.hpp"
#include "python/bindings.hpp"
#include "python/progress.hpp"
#include "runs/files.hpp"
#include "runs/run.hpp"
#include "scene/scene.hpp"

#include <toml++/toml.h>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace nsb::python {

namespace {

// The Python name of a value's type ("NoneType", "dict", ...), for messages.
std::string type_name(const py::handle& v) {
  return py::type::of(v).attr("__name__").cast<std::string>();
}

// Where a converted value goes: a table's key, or the end of an array.
struct Slot {
  toml::table* table = nullptr;
  std::string name;
  toml::array* array = nullptr;

  template <class T>
  void put(T&& value) const {
    if (table != nullptr) {
      table->insert(name, std::forward<T>(value));
    } else {
      array->push_back(std::forward<T>(value));
    }
  }
};

void put_node(const py::handle& v, const std::string& origin, const std::string& key,
              const Slot& slot);

// A dict as a scene table, the key path of a value as the scene's messages write it
// ("model.bents[0].height"); put_node converts each value.
toml::table to_table(const py::dict& d, const std::string& origin, const std::string& path) {
  toml::table t;
  for (const auto& [k, v] : d) {
    if (!py::isinstance<py::str>(k)) {
      throw std::invalid_argument(origin + ": " + (path.empty() ? "" : path + ": ") +
                                  "expected str keys, got the " + type_name(k) + " " +
                                  py::repr(k).cast<std::string>());
    }
    const std::string name = k.cast<std::string>();
    put_node(v, origin, path.empty() ? name : path + "." + name, Slot{&t, name, nullptr});
  }
  return t;
}

// A Python value as the TOML node of a scene table: a dict is a table (str keys), a list or
// tuple an array (of tables when its elements are dicts), a bool a boolean, an int an integer
// (64 bits), a float a float, a str a string. Anything else is bad input, "<origin>: <key>:
// ...".
void put_node(const py::handle& v, const std::string& origin, const std::string& key,
              const Slot& slot) {
  if (py::isinstance<py::bool_>(v)) {
    slot.put(v.cast<bool>());
  } else if (PyLong_Check(v.ptr())) {
    try {
      slot.put(v.cast<std::int64_t>());
    } catch (const py::cast_error&) {
      throw std::invalid_argument(origin + ": " + key + ": the integer " +
                                  py::repr(v).cast<std::string>() + " does not fit in 64 bits");
    }
  } else if (PyFloat_Check(v.ptr())) {
    slot.put(v.cast<double>());
  } else if (py::isinstance<py::str>(v)) {
    slot.put(v.cast<std::string>());
  } else if (py::isinstance<py::dict>(v)) {
    slot.put(to_table(v.cast<py::dict>(), origin, key));
  } else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    toml::array a;
    std::size_t i = 0;
    for (const auto& e : v) {
      put_node(e, origin, key + "[" + std::to_string(i++) + "]", Slot{nullptr, {}, &a});
    }
    slot.put(std::move(a));
  } else {
    throw std::invalid_argument(origin + ": " + key + ": expected a dict, a list, a bool, an " +
                                "int, a float or a str, got " + type_name(v));
  }
}

// The typed override of one Python value: a str is the text after "=" (scene::parse_override's
// rule, as on the command line); a bool, an int, a float or a list or tuple of numbers is
// taken as it is.
scene::Override to_override(const std::string& key, const py::handle& v) {
  if (py::isinstance<py::str>(v)) return scene::parse_override(key + "=" + v.cast<std::string>());
  if (py::isinstance<py::bool_>(v)) return {key, v.cast<bool>()};
  if (PyLong_Check(v.ptr())) {
    try {
      return {key, v.cast<std::int64_t>()};
    } catch (const py::cast_error&) {
      throw std::invalid_argument("override \"" + key + "\": the integer " +
                                  py::repr(v).cast<std::string>() + " does not fit in 64 bits");
    }
  }
  if (PyFloat_Check(v.ptr())) return {key, v.cast<double>()};
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    std::vector<double> x;
    for (const auto& e : v) {
      if (py::isinstance<py::bool_>(e) || !(PyLong_Check(e.ptr()) || PyFloat_Check(e.ptr()))) {
        throw std::invalid_argument("override \"" + key + "\": expected a list of numbers, " +
                                    "got an element of type " + type_name(e));
      }
      x.push_back(e.cast<double>());
    }
    return {key, std::move(x)};
  }
  throw std::invalid_argument("override \"" + key + "\": expected a bool, an int, a float, " +
                              "a str or a list of numbers, got " + type_name(v));
}

// The overrides of a Python argument, in order: a dict {"section.key": value} (to_override),
// a list of "section.key=value" strings, or one such string; None is none.
std::vector<scene::Override> to_overrides(const py::handle& arg) {
  std::vector<scene::Override> out;
  if (arg.is_none()) return out;
  if (py::isinstance<py::str>(arg)) return {scene::parse_override(arg.cast<std::string>())};
  if (py::isinstance<py::dict>(arg)) {
    for (const auto& [k, v] : arg.cast<py::dict>()) {
      if (!py::isinstance<py::str>(k)) {
        throw std::invalid_argument("overrides: expected str keys (\"section.key\"), got " +
                                    type_name(k));
      }
      out.push_back(to_override(k.cast<std::string>(), v));
    }
    return out;
  }
  if (py::isinstance<py::list>(arg) || py::isinstance<py::tuple>(arg)) {
    for (const auto& e : arg) {
      if (!py::isinstance<py::str>(e)) {
        throw std::invalid_argument("overrides: expected \"section.key=value\" strings in a " +
                                    std::string("list, got ") + type_name(e) +
                                    " (typed values go in a dict {\"section.key\": value})");
      }
      out.push_back(scene::parse_override(e.cast<std::string>()));
    }
    return out;
  }
  throw std::invalid_argument("overrides: expected a dict {\"section.key\": value}, a list of " +
                              std::string("\"section.key=value\" strings or one such string, got ") +
                              type_name(arg));
}

// nsbridge.Scene: a scene value (its table, overrides applied) built and checked once
// (runs::prepare), and what the check found. A run builds the system again from the table,
// since a run consumes its system; it reads no scene file, only the scene's record files.
struct PyScene {
  scene::SceneTable table;
  std::optional<std::filesystem::path> path;  // the scene file; none for a dict
  std::vector<std::string> overrides;         // the overrides applied, in text form, in order
  std::string name, kind, method;
  double end_time = 0.0;                      // [s]
  std::vector<std::string> warnings;          // the step warnings found before a run (runs/trust.hpp)
};

// The scene of a request, built and checked (runs::prepare) with the GIL released.
PyScene check_scene(const runs::RunRequest& request, std::optional<std::filesystem::path> path,
                    std::vector<std::string> overrides) {
  runs::PreparedRun p;
  {
    py::gil_scoped_release release;
    p = runs::prepare(request);
  }
  return PyScene{std::move(p.scene.table),
                 std::move(path),
                 std::move(overrides),
                 p.scene.name,
                 p.scene.kind,
                 std::string(integrators::method_name(p.scene.run)),
                 integrators::end_time(p.scene.run),
                 std::move(p.warnings)};
}

std::vector<std::string> texts(const std::vector<scene::Override>& overrides) {
  std::vector<std::string> out;
  for (const auto& o : overrides) out.push_back(scene::to_string(o));
  return out;
}

PyScene load_scene(const std::filesystem::path& path, const py::object& overrides) {
  runs::RunRequest request;
  request.scene = path;
  request.typed_overrides = to_overrides(overrides);
  return check_scene(request, path, texts(request.typed_overrides));
}

PyScene scene_from_dict(const py::dict& d, const std::string& name,
                        const std::filesystem::path& folder) {
  runs::RunRequest request;
  request.scene = scene::SceneTable{to_table(d, name, ""), {name, folder}, {}};
  return check_scene(request, std::nullopt, {});
}

PyScene with_overrides(const PyScene& s, const py::object& overrides) {
  runs::RunRequest request;
  request.scene = s.table;
  request.typed_overrides = to_overrides(overrides);
  std::vector<std::string> all = s.overrides;
  for (auto& t : texts(request.typed_overrides)) all.push_back(std::move(t));
  return check_scene(request, s.path, std::move(all));
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
      io::check_output_dir(dir);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("Result.write: ") + e.what());
    }
    runs::write_record(dir, record_);
  }

 private:
  runs::RunRecord record_;
  py::object summary_, history_, events_;  // null until first asked for
};

// run(scene_or_path, method, overrides, progress, cross_check): the request (a Scene's table,
// or a path), then runs::prepare and runs::run with the GIL released, so that other Python
// threads run meanwhile.
Result run(const py::object& scene, const std::optional<std::string>& method,
           const py::object& overrides, const py::object& progress,
           const std::optional<std::string>& cross_check) {
  runs::RunRequest request;
  if (py::isinstance<PyScene>(scene)) {
    request.scene = scene.cast<const PyScene&>().table;
  } else if (py::isinstance<py::str>(scene) || py::hasattr(scene, "__fspath__")) {
    request.scene = scene.cast<std::filesystem::path>();
  } else {
    throw py::type_error("run: scene_or_path: expected a Scene or a path");
  }
  request.typed_overrides = to_overrides(overrides);
  request.method = method.value_or("");
  request.cross_check = cross_check.value_or("");
  ProgressReport report(progress);
  request.stop = report.stop();
  std::optional<runs::RunRecord> record;
  {
    py::gil_scoped_release release;
    runs::PreparedRun prepared = runs::prepare(request);
    report.start(integrators::end_time(prepared.scene.run));
    record.emplace(runs::run(std::move(prepared), report.callback()));
  }
  report.finish();  // raises KeyboardInterrupt, or what a progress callable raised
  return Result(std::move(*record));
}

// scene_criterion(scene_or_path, friction): eta of each end of a scene's one deck, as
// `nsbridge criterion --scene FILE --json`.
py::dict scene_criterion(const py::object& scene, std::optional<double> friction) {
  scene::Scene built;
  if (py::isinstance<PyScene>(scene)) {
    built = scene::build_scene(scene.cast<const PyScene&>().table);
  } else if (py::isinstance<py::str>(scene) || py::hasattr(scene, "__fspath__")) {
    built = scene::load_scene(scene.cast<std::filesystem::path>());
  } else {
    throw py::type_error("scene_criterion: scene_or_path: expected a Scene or a path");
  }
  if (!built.design) {
    throw std::invalid_argument(
        "scene_criterion: " + built.name + ": [model] kind = \"" + built.kind +
        "\" has no deck of one body (a bridge of one deck or a rigid_deck); for a frame of a "
        "bridge in segments give its plan to nsbridge.end_criterion");
  }
  return plan_criterion_dict(built.design->deck, friction.value_or(built.design->friction));
}

std::string scene_repr(const PyScene& s) {
  return "Scene('" + (s.path ? s.path->string() : s.table.origin.name) + "', name='" + s.name +
         "', method='" + s.method + "', end_time=" + io::three_digits(s.end_time) + ")";
}

void bind_scene(py::module_& m) {
  py::class_<PyScene>(m, "Scene",
                      "A scene, built and checked: from a file (nsbridge.load_scene) or a dict "
                      "(Scene.from_dict)")
      .def_static("from_dict", &scene_from_dict, py::arg("d"), py::arg("name") = "scene",
                  py::arg("folder") = std::filesystem::path("."),
                  "A scene from a nested dict with the scene file's keys (tables as dicts, "
                  "arrays of tables as lists of dicts), checked as a file is; name stands for "
                  "the file in messages, record files are looked up from folder. Bad input "
                  "raises InputError naming the key")
      .def_property_readonly(
          "path", [](const PyScene& s) { return s.path; },
          "The scene file (pathlib.Path); None for a scene from a dict")
      .def_readonly("overrides", &PyScene::overrides,
                    "The overrides applied, \"section.key=value\" (the value as TOML), in order")
      .def_readonly("name", &PyScene::name,
                    "The scene's name (the file's stem; from_dict's name)")
      .def_readonly("kind", &PyScene::kind, "[model] kind")
      .def_readonly("method", &PyScene::method,
                    "solver.method: 'moreau', 'event_driven' or 'compliance'")
      .def_readonly("end_time", &PyScene::end_time, "solver.end_time [s]")
      .def_readonly("warnings", &PyScene::warnings, "Step warnings found before a run")
      .def("with_overrides", &with_overrides, py::arg("overrides"),
           "A new Scene: these overrides (a dict {\"section.key\": value}, a list of "
           "\"section.key=value\" strings or one such string) applied to this one's table, "
           "checked; no file is read")
      .def("to_toml", [](const PyScene& s) { return scene::to_toml(s.table); },
           "The scene's TOML text, overrides applied: read back, it is the same scene")
      .def("__repr__", &scene_repr);
  m.def("load_scene", &load_scene, py::arg("path"), py::arg("overrides") = py::none(),
        "Loads and checks a scene file (TOML, docs/scenes.md) with overrides (a dict "
        "{\"section.key\": value}, a list of \"section.key=value\" strings or one such "
        "string); bad input raises InputError naming the file, line and key");
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
      .def_property_readonly(
          "peaks", [](Result& r) -> py::object { return r.summary()["peaks"]; },
          "summary.json's peaks: {column: {max, t_max, min, t_min, abs_max, t_abs_max, error}} "
          "over every accepted step; error is abs_max's estimated error (None when not "
          "estimated; docs/error-estimates.md)")
      .def_property_readonly(
          "error_estimate", [](Result& r) -> py::object { return r.summary()["error_estimate"]; },
          "summary.json's error_estimate: the companion run, the order and factor of the "
          "extrapolation, impacts and first_impact with their errors, impact_order, cost "
          "(docs/error-estimates.md)")
      .def_property_readonly(
          "accuracy", [](Result& r) -> py::object { return r.summary()["accuracy"]; },
          "summary.json's accuracy: {target, met, step or tolerance, worst, "
          "worst_relative_error}; met is None without an estimate; with solver.adapt also "
          "adapt, attempts and total_cpu_seconds")
      .def_property_readonly(
          "cross_check",
          [](Result& r) -> py::object {
            const py::dict s = r.summary().cast<py::dict>();
            return s.contains("cross_check") ? py::object(s["cross_check"]) : py::none();
          },
          "summary.json's cross_check: the other method's peaks with their errors and the "
          "differences, its impacts and first impact (None without a cross-check)")
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
  m.def("scene_criterion", &scene_criterion, py::arg("scene_or_path"),
        py::arg("friction") = py::none(),
        "The rotation criterion eta of each end of a scene's one deck (a Scene or a path), "
        "at the seats' friction unless `friction` is given: the keys of `nsbridge criterion "
        "--scene FILE --json`");
  m.def("run", &run, py::arg("scene_or_path"), py::arg("method") = py::none(),
        py::arg("overrides") = py::none(), py::arg("progress") = false,
        py::arg("cross_check") = py::none(),
        "Runs a scene (a Scene or a path) with `nsbridge run`'s pipeline, the GIL released; "
        "method overrides solver.method; progress: False, True (a line on stderr) or a "
        "callable f(t); cross_check: a second method the scene is run under and compared with "
        "(Result.cross_check). A numerical failure is Result.status, bad input raises "
        "InputError");
}

}  // namespace nsb::python
