#include "app/run_plot.hpp"

#include "app/commands.hpp"
#include "io/gnuplot.hpp"
#include "io/csv.hpp"
#include "io/json_reader.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>

namespace nsb::app {

namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------
// The run folder as the figure reads it.

struct Event {
  double t = 0.0;
  int contact = 0;
  std::string kind;
};

struct RunFolder {
  fs::path history;                  // absolute path of history.csv
  std::vector<std::string> columns;  // its header
  std::size_t rows = 0;
  std::string scene, method, status;
  double end_time = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::pair<std::string, std::string>> contacts;  // (family, name) per contact
};

std::string read_text(const fs::path& file, const std::string& what) {
  std::error_code ec;
  if (!fs::exists(file, ec)) {
    throw InputError(file.string() + ": not found; a run folder holds " + what +
                     " as `nsbridge run` writes it (docs/outputs.md)");
  }
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(file.string() + ": cannot be read");
  return text.str();
}

// The fields of one CSV line split at commas (no field of the history is quoted).
std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

// A number as history.csv writes it: the shortest round-trip form, or empty (not finite).
bool is_number(std::string_view field) {
  if (field.empty()) return true;
  const std::string text(field);
  char* end = nullptr;
  errno = 0;
  std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && !std::isspace(static_cast<unsigned char>(text[0]));
}

// history.csv's header and row count; every row checked: as many fields as the header,
// each a number or empty.
void read_history(RunFolder& run) {
  const std::string text = read_text(run.history, "history.csv");
  const std::string file = run.history.string();
  std::size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    ++line_no;
    if (line_no == 1) {
      for (auto f : split(line)) run.columns.emplace_back(f);
      if (run.columns.empty() || run.columns[0] != "t" || run.columns.size() < 2) {
        throw InputError(file + ":1: expected a header starting with t, then the run's columns");
      }
      for (std::size_t c = 0; c < run.columns.size(); ++c) {
        if (run.columns[c].empty())
          throw InputError(file + ":1: column " + std::to_string(c + 1) + " has no name");
      }
      continue;
    }
    if (line.empty() && pos >= text.size()) break;
    const auto fields = split(line);
    if (fields.size() != run.columns.size()) {
      throw InputError(file + ":" + std::to_string(line_no) + ": " +
                       std::to_string(fields.size()) + " fields, expected " +
                       std::to_string(run.columns.size()) + " as in the header");
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      if (!is_number(fields[c]) || (c == 0 && fields[c].empty())) {
        throw InputError(file + ":" + std::to_string(line_no) + ": column " + run.columns[c] +
                         ": '" + std::string(fields[c]) + "' is not a number");
      }
    }
    ++run.rows;
  }
  if (run.columns.empty()) throw InputError(file + ": empty; expected a header and samples");
  if (run.rows == 0) throw InputError(file + ": no samples after the header");
}

void read_summary(RunFolder& run, const fs::path& dir) {
  const fs::path path = dir / "summary.json";
  io::JsonValue summary;
  try {
    summary = io::parse_json(read_text(path, "summary.json"));
  } catch (const io::JsonError& e) {
    throw InputError(path.string() + ": not a summary.json as `nsbridge run` writes it: " +
                     e.what());
  }
  if (summary.type != io::JsonValue::Type::kObject)
    throw InputError(path.string() + ": expected a JSON object");
  run.scene = summary.string_member("scene");
  run.method = summary.string_member("method");
  run.status = summary.string_member("status");
  if (run.method.empty()) throw InputError(path.string() + ": method: missing");
  if (const io::JsonValue* t = summary.find("end_time");
      t != nullptr && t->type == io::JsonValue::Type::kNumber)
    run.end_time = t->number;
  // "contacts" names each contact's family; a summary written before it had none.
  if (const io::JsonValue* contacts = summary.find("contacts");
      contacts != nullptr && contacts->type == io::JsonValue::Type::kArray) {
    for (const io::JsonValue& c : contacts->items) {
      run.contacts.emplace_back(c.string_member("family"), c.string_member("name"));
    }
  }
}

std::vector<Event> read_events(const fs::path& dir) {
  const fs::path path = dir / "events.csv";
  const std::string text = read_text(path, "events.csv");
  std::vector<Event> events;
  std::istringstream in(text);
  std::string line;
  std::size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_no == 1) {
      if (line.rfind("t,contact,kind", 0) != 0)
        throw InputError(path.string() + ":1: expected the header t,contact,kind,note");
      continue;
    }
    if (line.empty()) continue;
    // t, contact and kind hold no comma; the note (quoted when it holds one) is not read.
    const auto fields = split(line);
    const std::string where = path.string() + ":" + std::to_string(line_no) + ": ";
    if (fields.size() < 3) throw InputError(where + "expected t,contact,kind,note");
    Event e;
    const std::string t(fields[0]), contact(fields[1]);
    char* end = nullptr;
    e.t = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size()) throw InputError(where + "t: not a number");
    const long k = std::strtol(contact.c_str(), &end, 10);
    if (contact.empty() || end != contact.c_str() + contact.size() || k < 0 || k > 1000000)
      throw InputError(where + "contact: not a contact number");
    e.contact = static_cast<int>(k);
    e.kind = std::string(fields[2]);
    events.push_back(std::move(e));
  }
  if (line_no == 0) throw InputError(path.string() + ": empty; expected the header t,contact,kind,note");
  return events;
}

// ---------------------------------------------------------------------------------------
// The history's columns by what they are.

// name = prefix + digits (digits may be empty when allow_bare): the digits' value, 0 for
// none; nullopt when name is not of that form.
std::optional<int> indexed(const std::string& name, std::string_view prefix, bool allow_bare) {
  if (name.rfind(prefix, 0) != 0) return std::nullopt;
  const std::string rest = name.substr(prefix.size());
  if (rest.empty()) return allow_bare ? std::optional<int>(0) : std::nullopt;
  if (rest.size() > 6 || !std::all_of(rest.begin(), rest.end(),
                                      [](unsigned char c) { return std::isdigit(c) != 0; }))
    return std::nullopt;
  return std::stoi(rest);
}

// One curve: a history column (1-based for gnuplot) against t or against another column.
struct Curve {
  int x = 1, y = 0;
  std::string title;
};

struct Panel {
  std::string title, xlabel = "t [s]", ylabel;
  std::vector<Curve> curves{};
  bool zero_line = false;  // a dashed line at y = 0 (the gap at which a contact closes)
};

std::string method_title(const std::string& method) {
  if (method == "moreau") return "Moreau-Jean time stepping";
  if (method == "event_driven") return "event-driven";
  if (method == "compliance") return "compliance (penalty)";
  return method;
}

std::string family_title(const std::string& family) {
  if (family == "abutment") return "abutments";
  if (family == "hinge") return "hinges";
  if (family == "shear_key") return "shear keys";
  if (family.empty()) return "contacts";
  return family;
}

// Contacts 1..n grouped by family: abutments, hinges, shear keys, then any other family in
// the order met, then the contacts without one.
std::vector<std::pair<std::string, std::vector<int>>> families(const RunFolder& run, int n) {
  std::vector<std::pair<std::string, std::vector<int>>> groups;
  auto family_of = [&run](int k) {
    return static_cast<std::size_t>(k) <= run.contacts.size()
               ? run.contacts[static_cast<std::size_t>(k - 1)].first
               : std::string();
  };
  std::vector<std::string> order = {"abutment", "hinge", "shear_key"};
  for (int k = 1; k <= n; ++k) {
    const std::string f = family_of(k);
    if (!f.empty() && std::find(order.begin(), order.end(), f) == order.end()) order.push_back(f);
  }
  order.emplace_back();
  for (const auto& f : order) {
    std::vector<int> members;
    for (int k = 1; k <= n; ++k) {
      if (family_of(k) == f) members.push_back(k);
    }
    if (!members.empty()) groups.emplace_back(f, std::move(members));
  }
  return groups;
}

std::string contact_title(const RunFolder& run, int k) {
  const auto i = static_cast<std::size_t>(k - 1);
  const std::string name = i < run.contacts.size() ? run.contacts[i].second : std::string();
  return std::to_string(k) + (name.empty() ? "" : ": " + name);
}

class Columns {
 public:
  explicit Columns(const std::vector<std::string>& names) : names_(names) {}
  // The 1-based column of name; 0 when absent.
  int at(const std::string& name) const {
    const auto it = std::find(names_.begin(), names_.end(), name);
    return it == names_.end() ? 0 : static_cast<int>(it - names_.begin()) + 1;
  }
  // The largest k with column prefix + k.
  int count(std::string_view prefix) const {
    int n = 0;
    for (const auto& c : names_) {
      if (auto k = indexed(c, prefix, false)) n = std::max(n, *k);
    }
    return n;
  }
  const std::vector<std::string>& names() const { return names_; }

 private:
  const std::vector<std::string>& names_;
};

// Displacement and rotation panels: x<b>, y<b> [m]; theta<b> [rad].
void body_panels(const Columns& cols, std::vector<Panel>& panels) {
  Panel disp{.title = "displacements", .ylabel = "displacement [m]"};
  Panel rot{.title = "rotations", .ylabel = "rotation [rad]"};
  // A deck (a body with theta) moves along (x) and across (y) the bridge; bodies 1..N of a
  // model in parts are named by their number.
  const bool deck = cols.at("theta") != 0;
  for (const auto& name : cols.names()) {
    const int c = cols.at(name);
    for (const char* q : {"x", "y", "theta"}) {
      const auto body = indexed(name, q, true);
      if (!body) continue;
      std::string title = name;
      if (*body > 0) title += " (body " + std::to_string(*body) + ")";
      else if (deck && name == "x") title += " (longitudinal)";
      else if (deck && name == "y") title += " (transverse)";
      (name.rfind("theta", 0) == 0 ? rot : disp).curves.push_back({1, c, title});
    }
  }
  if (!disp.curves.empty()) panels.push_back(std::move(disp));
  if (!rot.curves.empty()) panels.push_back(std::move(rot));
}

// One panel per contact family of the column prefix + k (gN: gaps, lambdaN: normal forces).
void contact_panels(const RunFolder& run, const Columns& cols, const std::string& prefix,
                    const std::string& quantity, const std::string& unit,
                    std::vector<Panel>& panels) {
  const int n = cols.count(prefix);
  for (const auto& [family, members] : families(run, n)) {
    Panel p{.title = family_title(family), .ylabel = quantity + " [" + unit + "]"};
    p.zero_line = prefix == "gN";
    for (int k : members) {
      if (const int c = cols.at(prefix + std::to_string(k)))
        p.curves.push_back({1, c, prefix + contact_title(run, k)});
    }
    if (!p.curves.empty()) panels.push_back(std::move(p));
  }
}

std::vector<Panel> response_panels(const RunFolder& run, const Columns& cols) {
  std::vector<Panel> panels;
  body_panels(cols, panels);
  // Gaps rather than forces: a sampled row rarely holds an impact (an impulse within one step),
  // while the gap shows every closing, how near and how deep, under every method.
  contact_panels(run, cols, "gN", "normal gap", "m", panels);
  if (panels.empty()) {
    throw InputError(run.history.string() +
                     ": no coordinates (x, y, theta) and no contact columns to draw");
  }
  return panels;
}

std::vector<Panel> gap_panels(const RunFolder& run, const Columns& cols) {
  std::vector<Panel> panels;
  contact_panels(run, cols, "gN", "normal gap", "m", panels);
  if (panels.empty()) throw InputError(run.history.string() + ": no gap columns gN<k>: the run has no contacts");
  return panels;
}

// Hysteresis loops: bent i's force against its deformation, one panel per bent and direction.
std::vector<Panel> bent_panels(const RunFolder& run, const Columns& cols) {
  std::vector<int> bents;
  for (const auto& name : cols.names()) {
    if (name.rfind("bent", 0) != 0) continue;
    const std::size_t bar = name.find('_');
    if (bar == std::string::npos) continue;
    if (auto i = indexed(name.substr(0, bar), "bent", false);
        i && std::find(bents.begin(), bents.end(), *i) == bents.end())
      bents.push_back(*i);
  }
  std::sort(bents.begin(), bents.end());
  std::vector<Panel> panels;
  for (int i : bents) {
    const std::string b = "bent" + std::to_string(i);
    for (const auto& [dir, label] : {std::pair{"x", "longitudinal"}, std::pair{"y", "transverse"}}) {
      const int u = cols.at(b + "_u" + dir), f = cols.at(b + "_f" + dir);
      if (u == 0 || f == 0) continue;
      Panel p{.title = "bent " + std::to_string(i) + ", " + label,
              .xlabel = std::string("deformation u_") + dir + " [m]",
              .ylabel = std::string("force f_") + dir + " [kN]"};
      p.curves.push_back({u, f, b + "_f" + dir + " against " + b + "_u" + dir});
      panels.push_back(std::move(p));
    }
  }
  if (panels.empty()) {
    throw InputError(run.history.string() +
                     ": no bent columns (bent<i>_ux, bent<i>_fx, bent<i>_uy, bent<i>_fy): ask "
                     "the run for them with [output] groups = [\"bents\"] in the scene (or "
                     "--set 'output.groups=[\"bents\"]')");
  }
  return panels;
}

std::vector<Panel> energy_panels(const RunFolder& run, const Columns& cols) {
  std::vector<Panel> panels;
  Panel error{.title = "energy balance error", .ylabel = "relative error [-]"};
  Panel terms{.title = "energy terms", .ylabel = "energy [kJ]"};
  for (const auto& name : cols.names()) {
    if (name.rfind("energy_", 0) != 0) continue;
    if (name == "energy_error") error.curves.push_back({1, cols.at(name), name});
    else terms.curves.push_back({1, cols.at(name), name.substr(7)});
  }
  if (!error.curves.empty()) panels.push_back(std::move(error));
  if (!terms.curves.empty()) panels.push_back(std::move(terms));
  if (panels.empty()) throw InputError(run.history.string() + ": no energy_error column");
  return panels;
}

// ---------------------------------------------------------------------------------------
// The gnuplot scripts.

constexpr int kWidth = 1000;        // [px] of every figure
constexpr int kPanelHeight = 260;   // [px] of one row of panels
constexpr int kTitleHeight = 60;    // [px] of the figure's title

std::string preamble() {
  return "set encoding utf8\n"
         "set termoption noenhanced\n"  // names hold underscores, not subscripts
         "set datafile separator ','\n"
         "set grid\n"
         "set key outside right top Left reverse samplen 2\n"
         "set lmargin 13\n";
}

std::string figure_title(const RunFolder& run, const std::string& what) {
  std::string t = (run.scene.empty() ? std::string("run") : run.scene) + ": " + what + ", " +
                  method_title(run.method);
  if (!run.status.empty() && run.status != "completed") t += " (" + run.status + ")";
  return t;
}

std::string panels_script(const RunFolder& run, const std::string& title,
                          const std::vector<Panel>& panels, int columns, io::ImageSize& size) {
  const int rows = static_cast<int>((panels.size() + static_cast<std::size_t>(columns) - 1) /
                                    static_cast<std::size_t>(columns));
  size = {kWidth, kTitleHeight + rows * kPanelHeight, ""};
  std::string s = preamble();
  s += "set datafile columnheaders\n";
  // The legends stand right of the panels, in a margin as wide as the longest (in characters,
  // with the line sample), the same for every panel so that their time axes align.
  std::size_t longest = 0;
  for (const Panel& p : panels) {
    for (const Curve& c : p.curves) longest = std::max(longest, c.title.size());
  }
  s += "set rmargin " + std::to_string(std::clamp<std::size_t>(longest + 9, 16, 60)) + "\n";
  // Side by side, the deformation axes' tick labels are slanted so that they do not touch.
  if (columns > 1) s += "set rmargin 4\nset key off\nset xtics rotate by 30 right\n";
  s += "set multiplot layout " + std::to_string(rows) + "," + std::to_string(columns) +
       " title " + io::gnuplot_string(title) + " font ',13'\n";
  const std::string file = io::gnuplot_string(run.history.string());
  for (const Panel& p : panels) {
    s += "set title " + io::gnuplot_string(p.title) + "\n";
    s += "set xlabel " + io::gnuplot_string(p.xlabel) + "\n";
    s += "set ylabel " + io::gnuplot_string(p.ylabel) + "\n";
    s += "plot ";
    for (std::size_t i = 0; i < p.curves.size(); ++i) {
      const Curve& c = p.curves[i];
      s += (i ? ", \\\n     " : "") + file + " using " + std::to_string(c.x) + ":" +
           std::to_string(c.y) + " with lines lw 1.2 title " + io::gnuplot_string(c.title);
    }
    if (p.zero_line) s += ", \\\n     0 with lines dashtype 2 lc rgb 'black' notitle";
    s += "\n";
  }
  s += "unset multiplot\n";
  return s;
}

// Event times per contact: one row per contact (y), one point style per kind; warnings and
// events of no contact on row 0.
std::string events_script(const RunFolder& run, const std::vector<Event>& events,
                          const Columns& cols, io::ImageSize& size) {
  int n = cols.count("gN");
  for (const Event& e : events) n = std::max(n, e.contact);
  const bool row0 = std::any_of(events.begin(), events.end(),
                                [](const Event& e) { return e.contact == 0; });
  size = {kWidth, std::max(420, kTitleHeight + 140 + 26 * (n + 1)), ""};
  std::string s = preamble();
  s += "set title " + io::gnuplot_string(figure_title(run, "events per contact")) + " font ',13'\n";
  s += "set xlabel 't [s]'\nset ylabel 'contact (family, number: name)'\n";
  // Rows grouped by family, as the other figures' panels.
  std::vector<int> row(static_cast<std::size_t>(n) + 1, 0);
  std::string tics = "set ytics (";
  int y = 0;
  bool first = true;
  if (row0) {
    tics += "\"run (no contact)\" 0";
    first = false;
  }
  const auto groups = families(run, n);
  for (auto g = groups.rbegin(); g != groups.rend(); ++g) {
    for (auto k = g->second.rbegin(); k != g->second.rend(); ++k) {
      row[static_cast<std::size_t>(*k)] = ++y;
      tics += (first ? "" : ", ") + io::gnuplot_string(family_title(g->first) + " " + contact_title(run, *k)) + " " + std::to_string(y);
      first = false;
    }
  }
  s += tics + ")\n";
  // The rows' names left of the axis, the kinds' legend right of it.
  std::size_t longest = 16;
  for (int k = 1; k <= n; ++k) {
    longest = std::max(longest, contact_title(run, k).size() + 11);
  }
  s += "set lmargin " + std::to_string(std::min<std::size_t>(longest + 6, 60)) + "\nset rmargin 14\n";
  s += "set yrange [" + std::string(row0 ? "-0.7" : "0.3") + ":" + std::to_string(y) + ".7]\n";
  if (std::isfinite(run.end_time)) s += "set xrange [0:" + io::shortest(run.end_time) + "]\n";
  // Each kind a little above or below its contact's row, since the kinds of one impact
  // (impact, close, slip) share a time.
  struct Kind {
    const char* name;
    double offset;  // [rows]
    const char* style;
  };
  const Kind kinds[] = {{"impact", 0.0, "pt 7 ps 0.8 lc rgb 'black'"},
                        {"close", 0.24, "pt 9 ps 0.8 lc rgb '#1f5fbf'"},
                        {"open", -0.24, "pt 11 ps 0.8 lc rgb '#c03020'"},
                        {"stick", 0.12, "pt 5 ps 0.5 lc rgb '#2a9d4a'"},
                        {"slip", -0.12, "pt 2 ps 0.7 lc rgb '#d08000'"},
                        {"warning", 0.0, "pt 3 ps 1.4 lc rgb 'red'"}};
  std::vector<std::string> plots;
  for (const auto& [kind, offset, style] : kinds) {
    std::string block;
    for (const Event& e : events) {
      if (e.kind != kind || e.contact > n) continue;
      block += io::shortest(e.t) + "," +
               io::shortest(row[static_cast<std::size_t>(e.contact)] + offset) + "\n";
    }
    if (block.empty()) continue;
    s += std::string("$") + kind + " << EOD\n" + block + "EOD\n";
    plots.push_back(std::string("$") + kind + " using 1:2 with points " + style + " title '" +
                    kind + "'");
  }
  if (plots.empty()) {
    s += "set label 2 'no events' at graph 0.5, graph 0.5 center\n";
    plots.push_back("NaN notitle");
  }
  s += "plot ";
  for (std::size_t i = 0; i < plots.size(); ++i) s += (i ? ", \\\n     " : "") + plots[i];
  return s + "\n";
}

fs::path temporary_beside(const fs::path& out) {
  return out.parent_path() / ("." + out.filename().string() + ".tmp" + std::to_string(::getpid()) +
                              out.extension().string());
}

}  // namespace

fs::path default_plot_file(const fs::path& run_dir, const std::string& what) {
  return run_dir / (what + ".png");
}

std::string plot_run(const fs::path& run_dir, const std::string& what, const fs::path& out) {
  const auto& kinds = plot_kinds();
  if (std::find(kinds.begin(), kinds.end(), what) == kinds.end()) {
    throw InputError("--what " + what + ": expected response, gaps, bents, energy or events");
  }
  if (io::terminal_for(out).empty()) {
    throw InputError("--out " + out.string() + ": unsupported extension '" +
                     out.extension().string() + "'; expected .png, .svg or .pdf");
  }
  std::error_code ec;
  if (!fs::is_directory(run_dir, ec)) {
    throw InputError(run_dir.string() + ": no such run folder (expected the --out folder of "
                                        "`nsbridge run`, with history.csv, events.csv and "
                                        "summary.json)");
  }
  const fs::path out_dir = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(out_dir, ec))
    throw InputError("--out " + out.string() + ": no such folder " + out_dir.string());
  RunFolder run;
  run.history = fs::absolute(run_dir / "history.csv");
  read_history(run);
  read_summary(run, run_dir);
  const Columns cols(run.columns);
  io::ImageSize size;
  std::string script;
  if (what == "events") {
    script = events_script(run, read_events(run_dir), cols, size);
  } else if (what == "bents") {
    script = panels_script(run, figure_title(run, "bent hysteresis"), bent_panels(run, cols), 2, size);
  } else {
    const std::vector<Panel> panels = what == "response" ? response_panels(run, cols)
                                      : what == "gaps"   ? gap_panels(run, cols)
                                                         : energy_panels(run, cols);
    script = panels_script(run, figure_title(run, what == "gaps" ? "normal gaps" : what), panels, 1, size);
  }
  // Drawn under a hidden name beside `out`, then renamed: `out` is whole or untouched.
  const fs::path tmp = temporary_beside(out);
  const std::string failed = io::draw_gnuplot("gnuplot", script, tmp, size);
  if (!failed.empty()) {
    fs::remove(tmp, ec);
    return out.string() + ": " + failed;
  }
  fs::rename(tmp, out, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError("--out " + out.string() + ": cannot be written");
  }
  return {};
}

}  // namespace nsb::app
