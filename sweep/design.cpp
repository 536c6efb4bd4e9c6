#include "sweep/design.hpp"

#include "integrators/run.hpp"
#include "io/csv.hpp"
#include "scene/scene.hpp"
#include "scene/scene_reader.hpp"
#include "sweep/csv.hpp"
#include "sweep/expand.hpp"
#include "sweep/fragility_sweep.hpp"
#include "sweep/suites.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <variant>

namespace nsb::sweep {

namespace fs = std::filesystem;

std::string_view to_string(Mode m) {
  switch (m) {
    case Mode::kGrid:
      return "grid";
    case Mode::kLatin:
      return "latin";
    case Mode::kList:
      return "list";
    case Mode::kOat:
      return "oat";
  }
  return "grid";
}

namespace {

void check_keys(const scene::Source& c, const toml::table& t, const std::string& where,
                const std::set<std::string>& allowed) {
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (allowed.count(key) == 0) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      c.fail(&v, where.empty() ? key : where + "." + key, "unknown key (allowed: " + list + ")");
    }
  }
}

double number(const scene::Source& c, const toml::node& n, const std::string& key) {
  if (const auto v = n.value<double>(); v && (n.is_floating_point() || n.is_integer())) {
    if (!std::isfinite(*v)) c.fail(&n, key, "must be finite");
    return *v;
  }
  c.fail(&n, key, "must be a number");
}

// The label and the override of a TOML value: the override holds the value itself, the label
// its text (numbers in their shortest round-trip form, booleans as true/false).
Level value_level(const scene::Source& c, const toml::node& n, const std::string& key,
                  const std::string& fkey) {
  if (n.is_integer()) {
    const std::int64_t v = *n.value<std::int64_t>();
    return {std::to_string(v), {{fkey, v}}, ValueKind::kInteger};
  }
  if (n.is_floating_point()) {
    const double v = number(c, n, key);
    return {io::csv_number(v), {{fkey, v}}, ValueKind::kReal};
  }
  if (n.is_boolean()) {
    const bool v = *n.value<bool>();
    return {v ? "true" : "false", {{fkey, v}}, ValueKind::kBoolean};
  }
  if (n.is_string()) {
    const std::string v = *n.value<std::string>();
    return {v, {{fkey, v}}, ValueKind::kText};
  }
  c.fail(&n, key, "must be a number, a string or a boolean");
}

const toml::array& array_of(const scene::Source& c, const toml::node& n, const std::string& key) {
  const auto* a = n.as_array();
  if (a == nullptr) c.fail(&n, key, "must be an array");
  if (a->empty()) c.fail(&n, key, "must not be empty");
  return *a;
}

// [a, b, n]: n >= 1 points from a to b, both ends exact.
std::vector<double> spaced(const scene::Source& c, const toml::node& n, const std::string& key,
                           bool geometric) {
  const auto& a = array_of(c, n, key);
  if (a.size() != 3 || !a[2].is_integer()) c.fail(&n, key, "must be [first, last, count]");
  const double lo = number(c, a[0], key), hi = number(c, a[1], key);
  const std::int64_t count = *a[2].value<std::int64_t>();
  if (count < 1 || count > 100000) c.fail(&a[2], key, "count must be in 1..100000");
  if (geometric && (lo <= 0.0 || hi <= 0.0)) c.fail(&n, key, "both ends must be > 0");
  std::vector<double> v(static_cast<std::size_t>(count));
  for (std::int64_t i = 0; i < count; ++i) {
    const double s = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
    v[static_cast<std::size_t>(i)] =
        geometric ? std::exp(std::log(lo) + s * (std::log(hi) - std::log(lo)))
                  : lo * (1.0 - s) + hi * s;
  }
  v.front() = lo;
  v.back() = hi;
  return v;
}

// A record file named in the design: relative to the design's folder when it exists there,
// otherwise as written (the scene's own lookup then applies: docs/scenes.md).
std::string record_path(const fs::path& dir, const std::string& p) {
  const fs::path candidate = dir / p;
  if (fs::path(p).is_relative() && fs::exists(candidate))
    return candidate.lexically_normal().string();
  return p;
}

// The scene keys of a record's components (docs/scenes.md, [model.excitation]).
const std::vector<std::pair<std::string, std::string>>& record_components() {
  static const std::vector<std::pair<std::string, std::string>> c = {
      {"transverse", "model.excitation.transverse_record"},
      {"longitudinal", "model.excitation.longitudinal_record"}};
  return c;
}

// A level of `records`: {name, transverse, longitudinal}, each component a record file that
// becomes its scene key's override; the label is the name, else the first file's stem.
Level record_level(const scene::Source& c, const toml::node& r, const std::string& rw,
                   const fs::path& dir) {
  const auto* rt = r.as_table();
  if (rt == nullptr) c.fail(&r, rw, "each record must be a table {name, transverse, longitudinal}");
  check_keys(c, *rt, rw, {"name", "transverse", "longitudinal"});
  Level level;
  for (const auto& [component, scene_key] : record_components()) {
    if (const auto* p = rt->get(component)) {
      if (!p->is_string()) c.fail(p, rw + "." + component, "must be a file name");
      const std::string file = *p->value<std::string>();
      level.overrides.push_back({scene_key, record_path(dir, file)});
      if (level.label.empty()) level.label = fs::path(file).stem().string();
    }
  }
  if (level.overrides.empty()) c.fail(&r, rw, "a record needs transverse and/or longitudinal");
  if (const auto* name = rt->get("name")) {
    if (!name->is_string()) c.fail(name, rw + ".name", "must be a string");
    level.label = *name->value<std::string>();
  }
  return level;
}

// The levels of `suite` (a CSV whose `components` columns, default file_1 then file_2, hold the
// transverse and the longitudinal file) or `folder` (its .AT2 files, transverse), one per record
// (docs/sweep.md, "Record suites").
std::vector<Level> suite_levels(const scene::Source& c, const toml::table& t, const std::string& where,
                                const fs::path& dir) {
  const auto* suite = t.get("suite");
  const auto* comp = t.get("components");
  if (comp != nullptr && suite == nullptr) c.fail(comp, where + ".components", "only with suite");
  std::vector<std::string> columns{"file_1", "file_2"};
  if (comp != nullptr) {
    columns.clear();
    const auto& a = array_of(c, *comp, where + ".components");
    if (a.size() > record_components().size()) {
      c.fail(comp, where + ".components", "at most 2 columns: transverse, then longitudinal");
    }
    for (const auto& n : a) {
      if (!n.is_string()) c.fail(&n, where + ".components", "must hold column names");
      columns.push_back(*n.value<std::string>());
    }
  }
  const toml::node* n = suite != nullptr ? suite : t.get("folder");
  const std::string key = where + (suite != nullptr ? ".suite" : ".folder");
  if (!n->is_string()) c.fail(n, key, suite != nullptr ? "must be a CSV file" : "must be a folder");
  const fs::path path = dir / *n->value<std::string>();
  std::vector<SuiteRecord> records;
  try {
    records = suite != nullptr ? read_suite(path, columns) : read_folder(path);
  } catch (const std::invalid_argument& e) {
    c.fail(n, key, e.what());
  }
  std::vector<Level> levels;
  for (const auto& r : records) {
    Level level{r.name, {}};
    for (std::size_t i = 0; i < r.files.size(); ++i) {
      level.overrides.push_back({record_components()[i].second, r.files[i]});
    }
    levels.push_back(std::move(level));
  }
  return levels;
}

// A level of `levels`: {name, set}, a named list of overrides.
Level named_level(const scene::Source& c, const toml::node& l, const std::string& lw) {
  const auto* lt = l.as_table();
  if (lt == nullptr) c.fail(&l, lw, "each level must be a table {name, set}");
  check_keys(c, *lt, lw, {"name", "set"});
  const auto* name = lt->get("name");
  const auto* set = lt->get("set");
  if (name == nullptr || !name->is_string()) c.fail(&l, lw + ".name", "required string");
  if (set == nullptr) c.fail(&l, lw + ".set", "required: an array of \"key=value\"");
  Level level{*name->value<std::string>(), {}};
  for (const auto& s : array_of(c, *set, lw + ".set")) {
    if (!s.is_string()) c.fail(&s, lw + ".set", "must hold strings \"key=value\"");
    try {
      level.overrides.push_back(scene::parse_override(*s.value<std::string>()));
    } catch (const std::invalid_argument& e) {
      c.fail(&s, lw + ".set", e.what());
    }
  }
  return level;
}

Factor read_factor(const scene::Source& c, const toml::table& t, const fs::path& dir, std::size_t index,
                   Mode mode) {
  const std::string where = "factor[" + std::to_string(index) + "]";
  check_keys(c, t, where,
             {"key", "values", "linspace", "logspace", "range", "records", "levels", "suite",
              "folder", "components"});
  Factor f;
  f.line = static_cast<int>(t.source().begin.line);
  const auto* key = t.get("key");
  if (key == nullptr || !key->is_string() || key->value<std::string>()->empty()) {
    c.fail(key != nullptr ? key : &t, where + ".key", "required: the scene key (or a name)");
  }
  f.key = *key->value<std::string>();
  int given = 0;
  for (const char* k :
       {"values", "linspace", "logspace", "range", "records", "levels", "suite", "folder"}) {
    given += t.get(k) != nullptr ? 1 : 0;
  }
  if (given != 1) {
    c.fail(&t, where,
           "give exactly one of values, linspace, logspace, range, records, levels, suite, "
           "folder");
  }
  if (const auto* n = t.get("values")) {
    for (const auto& v : array_of(c, *n, where + ".values")) {
      f.levels.push_back(value_level(c, v, where + ".values", f.key));
    }
  }
  for (const bool geometric : {false, true}) {
    const std::string name = geometric ? "logspace" : "linspace";
    if (const auto* n = t.get(name)) {
      for (const double v : spaced(c, *n, where + "." + name, geometric)) {
        f.levels.push_back({io::csv_number(v), {{f.key, v}}, ValueKind::kReal});
      }
    }
  }
  if (const auto* n = t.get("range")) {
    if (mode != Mode::kLatin) c.fail(n, where + ".range", "only for mode = \"latin\"");
    const auto& a = array_of(c, *n, where + ".range");
    if (a.size() != 2) c.fail(n, where + ".range", "must be [low, high]");
    const double lo = number(c, a[0], where + ".range"), hi = number(c, a[1], where + ".range");
    if (!(lo < hi)) c.fail(n, where + ".range", "must have low < high");
    f.range = std::array<double, 2>{lo, hi};
  }
  if (const auto* n = t.get("records")) {
    for (const auto& r : array_of(c, *n, where + ".records")) {
      f.levels.push_back(record_level(c, r, where + ".records", dir));
    }
  }
  if (const auto* n = t.get("levels")) {
    for (const auto& l : array_of(c, *n, where + ".levels")) {
      f.levels.push_back(named_level(c, l, where + ".levels"));
    }
  }
  if (t.get("suite") != nullptr || t.get("folder") != nullptr) {
    f.levels = suite_levels(c, t, where, dir);
  }
  std::set<std::string> labels;
  for (const auto& l : f.levels) {
    if (!labels.insert(l.label).second)
      c.fail(&t, where, "level \"" + l.label + "\" appears twice");
  }
  return f;
}

// List mode: every row of the CSV is a run. A column named like a [[factor]] with records or
// levels selects a level by its name; any other column is a scene key and its cells values.
void expand_list(const scene::Source& c, const toml::node& runs_node, const fs::path& dir, Design& d) {
  if (!runs_node.is_string()) c.fail(&runs_node, "runs", "must be the name of a CSV file");
  const fs::path csv = dir / *runs_node.value<std::string>();
  std::ifstream in(csv);
  if (!in) c.fail(&runs_node, "runs", "cannot read " + csv.string());
  std::vector<Factor> named = std::move(d.factors);
  d.factors.clear();
  std::string line;
  int lineno = 0;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    auto fields = csv_fields(line);
    const std::string where = csv.string() + ":" + std::to_string(lineno);
    if (header.empty()) {
      header = fields;
      std::set<std::string> seen;
      for (const auto& h : header) {
        if (h.empty() || !seen.insert(h).second) {
          throw std::invalid_argument(where + ": column names must be non-empty and distinct");
        }
        Factor f;
        f.key = h;
        const auto it =
            std::find_if(named.begin(), named.end(), [&](const Factor& n) { return n.key == h; });
        if (it != named.end()) f = *it;
        d.factors.push_back(std::move(f));
      }
      continue;
    }
    if (fields.size() != header.size()) {
      throw std::invalid_argument(where + ": " + std::to_string(fields.size()) +
                                  " fields, the header has " + std::to_string(header.size()));
    }
    Run run;
    run.overrides = d.set;
    for (std::size_t k = 0; k < header.size(); ++k) {
      Factor& f = d.factors[k];
      const std::string& cell = fields[k];
      run.labels.push_back(cell);
      if (cell.empty()) continue;
      const auto named_it =
          std::find_if(named.begin(), named.end(), [&](const Factor& n) { return n.key == f.key; });
      if (named_it != named.end()) {
        const auto level = std::find_if(f.levels.begin(), f.levels.end(),
                                        [&](const Level& l) { return l.label == cell; });
        if (level == f.levels.end()) {
          throw std::invalid_argument(where + ": " + f.key + ": no level named \"" + cell + "\"");
        }
        run.overrides.insert(run.overrides.end(), level->overrides.begin(), level->overrides.end());
      } else {
        scene::Override o;
        try {
          o = scene::parse_override(f.key + "=" + cell);
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(where + ": " + e.what());
        }
        run.overrides.push_back(o);
        if (std::none_of(f.levels.begin(), f.levels.end(),
                         [&](const Level& l) { return l.label == cell; })) {
          f.levels.push_back({cell, {o}});
        }
      }
    }
    d.runs.push_back(std::move(run));
  }
  if (d.runs.empty()) c.fail(&runs_node, "runs", csv.string() + " holds no run");
}

// Everything a run's result depends on that the design controls: every run's labels and
// overrides, and the content hash of every input, with the design's folder written as "." so
// that moving the whole tree does not change the hash.
std::string design_hash(const Design& d) {
  const std::string dir = d.file.parent_path().lexically_normal().string();
  std::string text(to_string(d.mode));
  for (const auto& f : d.factors) text += '\x1f' + f.key;
  for (const auto& r : d.runs) {
    text += '\x1e';
    for (const auto& l : r.labels) text += l + '\x1f';
    for (const auto& override : r.overrides) {
      const std::string o = scene::to_string(override);
      std::size_t from = 0;
      for (auto p = dir.empty() ? std::string::npos : o.find(dir); p != std::string::npos;
           p = o.find(dir, from)) {
        text.append(o, from, p - from).append(".");
        from = p + dir.size();
      }
      text.append(o, from, std::string::npos).append("\x1f");
    }
  }
  for (const auto& input : d.inputs) text += '\x1e' + input.name + '\x1f' + input.hash;
  // A design without a cross-check hashes as it did before the key existed.
  if (!d.cross_check.empty()) text += "\x1e" "cross_check\x1f" + d.cross_check;
  return content_hash(text);
}

// A file's bytes; std::invalid_argument naming it when it cannot be read.
std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::invalid_argument(p.string() + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The record files a scene table names: every string whose key contains "record"
// (transverse_record, longitudinal_record, rotation_record_left, ...), by key path (array
// elements by 0-based index, as overrides name them).
void record_names(const toml::node& n, const std::string& path, std::string_view key,
                  std::map<std::string, std::string>& out) {
  if (const auto* t = n.as_table()) {
    for (const auto& [k, v] : *t) {
      const std::string name(k.str());
      record_names(v, path.empty() ? name : path + "." + name, k.str(), out);
    }
  } else if (const auto* a = n.as_array()) {
    for (std::size_t i = 0; i < a->size(); ++i)
      record_names((*a)[i], path + "." + std::to_string(i), key, out);
  } else if (n.is_string() && key.find("record") != std::string_view::npos) {
    out[path] = *n.value<std::string>();
  }
}

// Where a scene finds a record file (docs/scenes.md): absolute, next to the scene, in ../data/
// beside it, or in ./data/. Empty when none is a regular file (the run is then rejected with
// the scene's own message).
fs::path find_record(const fs::path& folder, const std::string& name) {
  const fs::path p(name);
  std::vector<fs::path> tried;
  if (p.is_absolute()) {
    tried.push_back(p);
  } else {
    tried.push_back(folder / p);
    tried.push_back(folder / ".." / "data" / p);
    tried.push_back(fs::current_path() / "data" / p);
  }
  for (const auto& t : tried) {
    std::error_code ec;
    if (fs::is_regular_file(t, ec)) return t.lexically_normal();
  }
  return {};
}

// The record files the runs read: the base scene's, replaced by a run's overrides of the same
// key, over every run.
std::set<fs::path> record_files(const Design& d) {
  std::map<std::string, std::string> base;
  record_names(d.base.table, "", "", base);
  std::set<std::string> names;
  for (const auto& run : d.runs) {
    std::map<std::string, std::string> named = base;
    for (const auto& o : run.overrides) {
      const auto* text = std::get_if<std::string>(&o.value);
      const std::string last = o.key.substr(o.key.find_last_of('.') + 1);
      if (text != nullptr && last.find("record") != std::string::npos) named[o.key] = *text;
    }
    for (const auto& [key, name] : named) names.insert(name);
  }
  std::set<fs::path> files;
  for (const auto& name : names) {
    if (fs::path f = find_record(d.base.origin.folder, name); !f.empty()) files.insert(f);
  }
  return files;
}

// A path relative to the design's folder, with '/' separators.
std::string input_name(const Design& d, const fs::path& p) {
  const fs::path absolute = fs::absolute(p).lexically_normal();
  return absolute.lexically_proximate(d.file.parent_path()).generic_string();
}

}  // namespace

namespace {

toml::table parse_design(const fs::path& file) {
  try {
    return toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << file.string() << ':' << e.source().begin.line << ':' << e.source().begin.column << ": "
      << e.description();
    throw std::invalid_argument(s.str());
  }
}

// `scene` (resolved against the design's folder) and `set`, then the command line's --set.
void read_scene(const scene::Source& c, const toml::table& root,
                const std::vector<std::string>& extra_set, Design& d) {
  const fs::path dir = d.file.parent_path();
  const auto* scene = root.get("scene");
  if (scene == nullptr || !scene->is_string())
    c.fail(scene, "scene", "required: the base scene file");
  d.scene = (dir / *scene->value<std::string>()).lexically_normal();
  if (!fs::is_regular_file(d.scene)) c.fail(scene, "scene", "no such file: " + d.scene.string());
  if (const auto* set = root.get("set")) {
    const auto* a = set->as_array();
    if (a == nullptr) c.fail(set, "set", "must be an array of \"key=value\"");
    for (const auto& s : *a) {
      if (!s.is_string() || s.value<std::string>()->find('=') == std::string::npos) {
        c.fail(&s, "set", "must hold strings \"key=value\"");
      }
      try {
        d.set.push_back(scene::parse_override(*s.value<std::string>()));
      } catch (const std::invalid_argument& e) {
        c.fail(&s, "set", e.what());
      }
    }
  }
  for (const auto& s : extra_set) {
    if (s.find('=') == std::string::npos)
      throw std::invalid_argument("--set " + s + ": must be key=value");
    try {
      d.set.push_back(scene::parse_override(s));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--set " + s + ": " + e.what());
    }
  }
}

// The [output] section: `hdf5_history`, the history columns `nsbridge sweep --hdf5` keeps in
// sweep.h5: "all" (the default), "none", or a list of history.csv column names (`t` is always
// kept). A name no run's history has is reported when sweep.h5 is written (the columns are
// the system's, known only once it is built).
void read_output(const scene::Source& c, const toml::table& root, Design& d) {
  const auto* node = root.get("output");
  if (node == nullptr) return;
  const auto* t = node->as_table();
  if (t == nullptr) c.fail(node, "output", "must be a table [output]");
  check_keys(c, *t, "output", {"hdf5_history"});
  const auto* h = t->get("hdf5_history");
  if (h == nullptr) return;
  d.output.line = static_cast<int>(h->source().begin.line);
  constexpr const char* kAllowed =
      "must be \"all\", \"none\" or an array of history.csv column names";
  if (const auto* a = h->as_array()) {
    d.output.history = OutputSpec::History::kColumns;
    std::set<std::string> seen;
    for (const auto& e : *a) {
      const auto name = e.value<std::string>();
      if (!e.is_string() || name->empty()) c.fail(&e, "output.hdf5_history", kAllowed);
      if (!seen.insert(*name).second)
        c.fail(&e, "output.hdf5_history", "\"" + *name + "\" appears twice");
      d.output.columns.push_back(*name);
    }
    return;
  }
  const std::string v = h->value<std::string>().value_or("");
  if (!h->is_string() || (v != "all" && v != "none")) c.fail(h, "output.hdf5_history", kAllowed);
  d.output.history = v == "all" ? OutputSpec::History::kAll : OutputSpec::History::kNone;
}

// `mode`, and the keys that only one mode takes: `samples` and `seed` (latin), `runs` (list).
void read_mode(const scene::Source& c, const toml::table& root, Design& d) {
  if (const auto* mode = root.get("mode")) {
    const std::string m = mode->value<std::string>().value_or("");
    if (m == "grid")
      d.mode = Mode::kGrid;
    else if (m == "latin")
      d.mode = Mode::kLatin;
    else if (m == "list")
      d.mode = Mode::kList;
    else if (m == "oat")
      d.mode = Mode::kOat;
    else
      c.fail(mode, "mode", "must be \"grid\", \"latin\", \"list\" or \"oat\"");
  }
  const auto* samples = root.get("samples");
  const auto* seed = root.get("seed");
  const auto* runs = root.get("runs");
  if (d.mode == Mode::kLatin) {
    if (samples == nullptr || !samples->is_integer() || *samples->value<std::int64_t>() < 1 ||
        *samples->value<std::int64_t>() > 1000000) {
      c.fail(samples != nullptr ? samples : &root, "samples",
             "latin: required integer in 1..1000000");
    }
    d.samples = *samples->value<std::int64_t>();
    if (seed != nullptr) {
      if (!seed->is_integer() || *seed->value<std::int64_t>() < 0)
        c.fail(seed, "seed", "must be an integer >= 0");
      d.seed = static_cast<std::uint64_t>(*seed->value<std::int64_t>());
    }
  } else {
    if (samples != nullptr) c.fail(samples, "samples", "only for mode = \"latin\"");
    if (seed != nullptr) c.fail(seed, "seed", "only for mode = \"latin\"");
  }
  if (d.mode == Mode::kList && runs == nullptr)
    c.fail(&root, "runs", "list: required CSV file of runs");
  if (d.mode != Mode::kList && runs != nullptr) c.fail(runs, "runs", "only for mode = \"list\"");
}

// `cross_check`: a method under which every run is run again and compared.
void read_cross_check(const scene::Source& c, const toml::table& root, Design& d) {
  const auto* node = root.get("cross_check");
  if (node == nullptr) return;
  const auto& names = integrators::method_names();
  const std::string method = node->value<std::string>().value_or("");
  if (!node->is_string() || std::find(names.begin(), names.end(), method) == names.end()) {
    std::string choices;
    for (const auto n : names) choices += (choices.empty() ? "\"" : ", \"") + std::string(n) + "\"";
    c.fail(node, "cross_check", "must be one of " + choices);
  }
  d.cross_check = method;
}

void read_factors(const scene::Source& c, const toml::table& root, Design& d) {
  const auto* factors = root.get("factor");
  if (factors == nullptr) return;
  const auto* a = factors->as_array();
  if (a == nullptr || !a->is_array_of_tables())
    c.fail(factors, "factor", "must be [[factor]] tables");
  std::set<std::string> keys;
  for (std::size_t k = 0; k < a->size(); ++k) {
    Factor f = read_factor(c, *(*a)[k].as_table(), d.file.parent_path(), k, d.mode);
    if (!keys.insert(f.key).second)
      c.fail(&(*a)[k], "factor[" + std::to_string(k) + "].key", "\"" + f.key + "\" appears twice");
    d.factors.push_back(std::move(f));
  }
}

// The runs of the mode, each with its id: its index, zero-padded to at least four digits.
void expand(const scene::Source& c, const toml::table& root, Design& d) {
  switch (d.mode) {
    case Mode::kGrid:
      if (d.factors.empty()) c.fail(&root, "factor", "grid: at least one [[factor]]");
      expand_grid(d);
      break;
    case Mode::kOat:
      if (d.factors.empty()) c.fail(&root, "factor", "oat: at least one [[factor]]");
      expand_oat(d);
      break;
    case Mode::kLatin:
      if (d.factors.empty()) c.fail(&root, "factor", "latin: at least one [[factor]]");
      expand_latin(d);
      break;
    case Mode::kList:
      expand_list(c, *root.get("runs"), d.file.parent_path(), d);
      break;
  }
  const std::size_t width = std::max<std::size_t>(4, std::to_string(d.runs.size() - 1).size());
  for (std::size_t i = 0; i < d.runs.size(); ++i) {
    std::string id = std::to_string(i);
    d.runs[i].id = std::string(width - id.size(), '0') + id;
  }
}

}  // namespace

Design load_design(const fs::path& file, const std::vector<std::string>& extra_set) {
  scene::Source c;
  c.file = file.string();
  const toml::table root = parse_design(file);
  check_keys(c, root, "",
             {"description", "scene", "set", "mode", "samples", "seed", "runs", "factor",
              "fragility", "output", "cross_check"});
  Design d;
  d.file = fs::absolute(file).lexically_normal();
  read_scene(c, root, extra_set, d);
  read_mode(c, root, d);
  read_output(c, root, d);
  read_cross_check(c, root, d);
  read_factors(c, root, d);
  expand(c, root, d);
  load_base_scene(d);
  d.fragility = read_fragility(root, d, c.file);
  return d;
}

void load_base_scene(Design& d) {
  const std::string where = d.file.string() + ": scene: ";
  std::string bytes;
  try {
    bytes = read_bytes(d.scene);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + e.what());
  }
  // The table scene::read_scene_table gives, parsed from the bytes that are hashed, so that the
  // file is opened once.
  d.base = scene::SceneTable{};
  d.base.origin.name = d.scene.string();
  d.base.origin.folder = d.scene.parent_path().empty() ? fs::path(".") : d.scene.parent_path();
  try {
    d.base.table = toml::parse(bytes, d.scene.string());
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << where << d.scene.string() << ':' << e.source().begin.line << ':'
      << e.source().begin.column << ": TOML syntax error: " << e.description();
    throw std::invalid_argument(s.str());
  }
  try {
    scene::SceneTable with_set = d.base;
    scene::apply_overrides(with_set, d.set);
    d.coordinates = scene::build_scene(with_set).system->coordinate_names();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + e.what());
  }
  d.inputs = {{input_name(d, d.scene), d.scene, content_hash(bytes)}};
  for (const auto& file : record_files(d)) {
    d.inputs.push_back({input_name(d, file), file, content_hash(read_bytes(file))});
  }
  d.hash = design_hash(d);
}

void validate_design(const Design& d) {
  const auto attempt = [&](const std::vector<scene::Override>& extra, const std::string& where) {
    try {
      scene::SceneTable t = d.base;
      scene::apply_overrides(t, d.set);
      scene::apply_overrides(t, extra);
      (void)scene::build_scene(t);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(d.file.string() + where + ": " + e.what());
    }
  };
  attempt({}, ": scene");
  for (std::size_t k = 0; k < d.factors.size(); ++k) {
    const Factor& f = d.factors[k];
    std::string at;
    if (f.line > 0) at.append(":").append(std::to_string(f.line));
    for (const Level& l : f.levels)
      attempt(l.overrides, at + ": factor " + f.key + " = " + l.label);
    if (f.range) {
      for (const double v : *f.range) {
        attempt({{f.key, v}},
                at + ": factor " + f.key + " = " + io::csv_number(v));
      }
    }
  }
}

const std::vector<std::string>& base_coordinates(const Design& d) { return d.coordinates; }

std::vector<scene::Override> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<scene::Override> out;
  out.reserve(texts.size());
  for (const auto& t : texts) out.push_back(scene::parse_override(t));
  return out;
}

std::string content_hash(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const unsigned char ch : bytes) {
    h ^= ch;
    h *= 0x100000001b3ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace nsb::sweep
