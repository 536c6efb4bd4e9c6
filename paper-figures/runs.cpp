#include "paper-figures/runs.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "scene/scene.hpp"
#include "sweep/csv.hpp"
#include "sweep/design.hpp"
#include "runs/run.hpp"
#include "sweep/runner.hpp"

namespace nsb::paper_figures {

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A field of history.csv: a shortest round-trip number, or empty for a non-finite value.
double parse_number(std::string_view f) {
  double v = std::numeric_limits<double>::quiet_NaN();
  if (!f.empty()) std::from_chars(f.data(), f.data() + f.size(), v);
  return v;
}

// Splits text at `sep` (the last piece may be empty).
std::vector<std::string_view> split(std::string_view text, char sep) {
  std::vector<std::string_view> out;
  std::size_t from = 0;
  for (std::size_t at = text.find(sep); at != std::string_view::npos; at = text.find(sep, from)) {
    out.push_back(text.substr(from, at - from));
    from = at + 1;
  }
  out.push_back(text.substr(from));
  return out;
}

}  // namespace

History::History(const integrators::Recorder& recorder) : columns_(recorder.columns()) {
  data_.reserve(recorder.rows() * columns_.size());
  for (std::size_t r = 0; r < recorder.rows(); ++r) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      const double v = recorder.at(r, c);
      data_.push_back(std::isfinite(v) ? v : std::numeric_limits<double>::quiet_NaN());
    }
  }
  for (integrators::Event e : recorder.events()) {
    if (!std::isfinite(e.t)) e.t = std::numeric_limits<double>::quiet_NaN();
    events_.push_back(std::move(e));
  }
}

History History::read(const fs::path& dir) {
  History h;
  const fs::path file = dir / "history.csv";
  const std::string text = read_text(file);
  std::vector<std::string_view> lines = split(text, '\n');
  if (!lines.empty() && lines.back().empty()) lines.pop_back();
  if (lines.empty()) throw std::runtime_error(file.string() + ": no header");
  for (auto c : split(lines[0], ',')) h.columns_.emplace_back(c);
  h.data_.reserve((lines.size() - 1) * h.columns_.size());
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto fields = split(lines[i], ',');
    if (fields.size() != h.columns_.size()) {
      throw std::runtime_error(file.string() + ":" + std::to_string(i + 1) + ": " +
                               std::to_string(fields.size()) + " fields for " +
                               std::to_string(h.columns_.size()) + " columns");
    }
    for (auto f : fields) h.data_.push_back(parse_number(f));
  }
  const sweep::Table ev = sweep::read_csv(dir / "events.csv");
  const std::size_t ct = ev.column("t"), cc = ev.column("contact"), ck = ev.column("kind"),
                    cn = ev.column("note");
  for (const auto& f : ev.rows) {
    const auto kind = integrators::parse_event_kind(f[ck]);
    if (!kind) throw std::runtime_error((dir / "events.csv").string() + ": kind \"" + f[ck] + "\"");
    h.events_.push_back({parse_number(f[ct]), std::stoi(f[cc]), *kind, f[cn]});
  }
  return h;
}

std::size_t History::column(std::string_view name) const {
  const auto it = std::find(columns_.begin(), columns_.end(), name);
  if (it == columns_.end()) throw std::out_of_range("history: no column " + std::string(name));
  return static_cast<std::size_t>(it - columns_.begin());
}

std::vector<double> History::series(std::string_view name) const {
  const std::size_t c = column(name);
  std::vector<double> v(rows());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = at(i, c);
  return v;
}

std::size_t History::count(integrators::EventKind kind) const {
  return static_cast<std::size_t>(std::count_if(
      events_.begin(), events_.end(), [&](const integrators::Event& e) { return e.kind == kind; }));
}

bool FigureRun::ok() const {
  const auto s = integrators::parse_run_status(status);
  return s && integrators::succeeded(*s);
}

std::string FigureRun::status_text() const {
  std::ostringstream s;
  s << spec.name << ": " << status << " at t = " << failure_time << " s";
  return s.str();
}

void RunSet::add(FigureRun r) {
  if (find(r.spec.name) != nullptr)
    throw std::logic_error("paper-figures: two runs named " + r.spec.name);
  runs_.push_back(std::move(r));
}

const FigureRun* RunSet::find(const std::string& name) const {
  for (const auto& r : runs_) {
    if (r.spec.name == name) return &r;
  }
  return nullptr;
}

const FigureRun& RunSet::at(const std::string& name) const {
  const FigureRun* r = find(name);
  if (r == nullptr) throw std::logic_error("paper-figures: no run named " + name);
  return *r;
}

namespace {

// The list design of the runs of one scene. The hash only names the design: the figures
// rewrite their folders every time (restart).
sweep::Design design_of(const fs::path& scene, const std::vector<const RunSpec*>& specs) {
  sweep::Design d;
  d.file = scene;
  d.scene = scene;
  d.mode = sweep::Mode::kList;
  d.factors.push_back({"run", {}, std::nullopt, 0});
  for (std::size_t i = 0; i < specs.size(); ++i) {
    std::ostringstream id;
    id << std::setw(5) << std::setfill('0') << i;
    d.runs.push_back({id.str(), {specs[i]->name}, sweep::parse_overrides(specs[i]->overrides)});
  }
  sweep::load_base_scene(d);
  d.hash = "figures-" + scene.stem().string() + "-" + std::to_string(specs.size());
  return d;
}

// Runs a design into dir and keeps every run's row and history, in the design's order.
std::vector<FigureRun> run_design(const sweep::Design& d, const std::vector<const RunSpec*>& specs,
                                  const fs::path& dir, int workers) {
  sweep::SweepOptions o;
  o.out = dir;
  o.jobs = workers;
  o.restart = true;
  o.progress = false;
  sweep::Plan plan = sweep::prepare(d, o);
  std::vector<History> histories(d.runs.size());  // one slot per run: no two threads share one
  sweep::run_threaded(d, o, plan, std::min<int>(workers, static_cast<int>(d.runs.size())), {},
                      [&histories](std::size_t index, const runs::RunRecord& record) {
                        histories[index] = History(record.history);
                      });
  sweep::write_results(d, o, plan.rows);
  std::vector<FigureRun> out;
  for (std::size_t i = 0; i < d.runs.size(); ++i) {
    FigureRun r;
    r.spec = *specs[i];
    r.status = "not_run";
    if (const auto& row = plan.rows[i]) {
      r.status = row->status;
      r.end_time = row->end_time;
      r.failure_time = row->failure_time;
    }
    r.history = std::move(histories[i]);
    out.push_back(std::move(r));
  }
  fs::remove_all(dir / "runs");
  return out;
}

}  // namespace

std::vector<FigureRun> make_runs(const std::vector<RunSpec>& specs, const fs::path& scenes,
                                 const fs::path& dir, int workers) {
  std::map<std::string, std::vector<const RunSpec*>> by_scene;
  for (const auto& s : specs) {
    scene::load_scene(scenes / (s.scene + ".toml"), s.overrides);
    by_scene[s.scene].push_back(&s);
  }
  std::map<std::string, FigureRun> made;
  for (const auto& [scene, list] : by_scene) {
    const sweep::Design d = design_of(scenes / (scene + ".toml"), list);
    for (auto& r : run_design(d, list, dir / scene, workers)) {
      made.emplace(r.spec.name, std::move(r));
    }
  }
  std::vector<FigureRun> out;
  for (const auto& s : specs) out.push_back(std::move(made.at(s.name)));
  return out;
}

// ---------------------------------------------------------------------------------------------
// Measures of one history.

double peak(const History& h, std::string_view column, double t_end) {
  const std::size_t c = h.column(column), ct = h.column("t");
  double p = 0.0;
  for (std::size_t i = 0; i < h.rows(); ++i) {
    if (h.at(i, ct) > t_end) break;
    p = std::max(p, std::abs(h.at(i, c)));
  }
  return p;
}

double value_at(const History& h, std::string_view column, double t) {
  const std::size_t ct = h.column("t"), c = h.column(column), n = h.rows();
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  if (t <= h.at(0, ct)) return h.at(0, c);
  if (t >= h.at(n - 1, ct)) return h.at(n - 1, c);
  // The first sample after t (samples ascending in t).
  std::size_t lo = 0, hi = n;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (h.at(mid, ct) <= t) lo = mid + 1;
    else hi = mid;
  }
  const std::size_t k = lo;
  const double w = (t - h.at(k - 1, ct)) / (h.at(k, ct) - h.at(k - 1, ct));
  return (1 - w) * h.at(k - 1, c) + w * h.at(k, c);
}

double normalized_rms_difference(const History& a, const History& b, std::string_view column,
                                 double t_end) {
  const std::size_t ct = a.column("t"), c = a.column(column);
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < a.rows() && a.at(i, ct) <= t_end; ++i) {
    const double va = a.at(i, c), vb = value_at(b, column, a.at(i, ct));
    num += (vb - va) * (vb - va);
    den += va * va;
  }
  return den > 0 ? std::sqrt(num / den) : std::numeric_limits<double>::quiet_NaN();
}

std::pair<double, int> first_impact(const History& h) {
  for (const auto& e : h.events()) {
    if (e.kind == integrators::EventKind::kImpact) return {e.t, e.contact};
  }
  return {0.0, 0};
}

}  // namespace nsb::paper_figures
