// The runs step of the uncertainty study: a design run through the sweep runner, its rows
// typed in memory, and the claims judged at one point from its runs' rows and outputs.
#include "paper-figures/uncertainty_steps.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "paper-figures/figures.hpp"
#include "scene/scene.hpp"
#include "sweep/csv.hpp"
#include "sweep/runner.hpp"

namespace nsb::paper_figures::uncertainty {

namespace fs = std::filesystem;

bool RunRow::ok() const {
  const auto s = integrators::parse_run_status(status);
  return s && integrators::succeeded(*s);
}

namespace {

double number_or_nan(const std::string& s) {
  if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
  try {
    return std::stod(s);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace

Rows run_design(const sweep::Design& d, const fs::path& dir, int workers, int& runs,
                std::vector<std::string>& failed) {
  sweep::SweepOptions o;
  o.out = dir;
  o.jobs = workers;
  o.restart = true;
  o.progress = false;
  sweep::Plan plan = sweep::prepare(d, o);
  sweep::run_threaded(d, o, plan, workers, {});
  const sweep::Results t = sweep::write_results(d, o, plan.rows);
  runs += static_cast<int>(plan.pending.size());
  const std::size_t point = t.column("point"), run = t.column("claim_run"),
                    peak = t.column(kTornadoResponse), impacts = t.column("impacts"),
                    end = t.column("end_time");
  const auto number = [&t](const sweep::Row& row, std::size_t column) {
    return t.number(row, column).value_or(std::numeric_limits<double>::quiet_NaN());
  };
  Rows rows;
  for (const auto& f : t.rows) {
    RunRow r;
    r.status = f.status;
    r.peak_theta = number(f, peak);
    r.impacts = static_cast<std::size_t>(std::max(0.0, number(f, impacts)));
    r.end_time = number(f, end);
    r.dir = dir / "runs" / f.run;
    const std::string at = t.cell(f, point), claim_run = t.cell(f, run);
    if (!r.ok())
      failed.push_back(dir.filename().string() + " " + f.run + " (" + at + ", " + claim_run +
                       "): " + r.status);
    rows[at][claim_run] = r;
  }
  return rows;
}

namespace {

// C6 from a run's outputs: its events and its recorded history of the sliding contact.
SlidingState sliding_state(const RunRow& r, double mu, std::string& failure) {
  const sweep::Table ev = sweep::read_csv(r.dir / "events.csv");
  const std::size_t ct = ev.column("t"), cc = ev.column("contact"), ck = ev.column("kind");
  std::vector<integrators::Event> events;
  for (const auto& f : ev.rows) {
    integrators::Event e;
    e.t = std::stod(f[ct]);
    e.contact = std::stoi(f[cc]);
    const auto kind = integrators::parse_event_kind(f[ck]);
    if (!kind) continue;
    e.kind = *kind;
    events.push_back(e);
  }
  std::vector<Sliding> slides = sliding_contacts(events, r.end_time);
  if (slides.empty()) {
    failure = "excitation 5 has no sliding contact";
    return SlidingState{};
  }
  const sweep::Table h = sweep::read_csv(r.dir / "history.csv");
  const std::size_t c_t = h.column("t");
  std::vector<double> t;
  for (const auto& f : h.rows) t.push_back(number_or_nan(f[c_t]));
  auto series = [&](const std::string& name) {
    const std::size_t c = h.column(name);
    std::vector<double> v;
    for (const auto& f : h.rows) v.push_back(number_or_nan(f[c]));
    return v;
  };
  // The history is recorded every sample_dt (5 ms), not every step: the longest slide that
  // holds a recorded sample is judged (the nominal C6 records every step of the longest).
  std::stable_sort(slides.begin(), slides.end(), [](const Sliding& a, const Sliding& b) {
    return a.end - a.start > b.end - b.start;
  });
  for (const auto& s : slides) {
    const std::string c = std::to_string(s.contact);
    SlidingState st = measure_sliding(s, mu, t, series("lambdaN" + c), series("lambdaT" + c));
    if (st.samples > 0) return st;
  }
  failure = "no recorded sample lies in a sliding contact of excitation 5";
  return SlidingState{};
}

}  // namespace

InputPga input_pgas(const fs::path& scenes, const std::vector<int>& excitations) {
  InputPga pga;
  for (int n : excitations) {
    const auto scene = scene::load_scene(scenes / ("bridge-exc" + std::to_string(n) + ".toml"));
    pga[n] = {input_pga(scene, true), input_pga(scene, false)};
  }
  return pga;
}

// The peaks of Fig. 6 at one point, from the rows of its runs (runs that were not made leave
// their numbers at the defaults; the claims then say which run is missing).
std::vector<Peaks> peaks_of(const std::map<std::string, RunRow>& runs,
                            const std::vector<int>& excitations, const InputPga& pga) {
  auto get = [&](const std::string& name) -> const RunRow* {
    const auto it = runs.find(name);
    return it == runs.end() ? nullptr : &it->second;
  };
  std::vector<Peaks> peaks;
  for (int n : excitations) {
    const std::string e = "exc" + std::to_string(n);
    const RunRow *p = get(e), *f = get(e + "-no-pounding"), *m = get(e + "-mu0");
    Peaks pk;
    pk.run = n;
    pk.pga_y = pga.at(n)[0];
    pk.pga_x = pga.at(n)[1];
    if (p != nullptr) pk.pounding = p->peak_theta, pk.impacts = p->impacts;
    if (f != nullptr) pk.free = f->peak_theta, pk.impacts_free = f->impacts;
    if (m != nullptr) pk.mu0 = m->peak_theta;
    peaks.push_back(pk);
  }
  return peaks;
}

std::vector<Claim> judge(const std::map<std::string, RunRow>& runs, double mu,
                         const InputPga& pga) {
  auto get = [&](const std::string& name) -> const RunRow* {
    const auto it = runs.find(name);
    return it == runs.end() ? nullptr : &it->second;
  };
  const std::vector<Peaks> peaks = peaks_of(runs, kStudyPgaRuns, pga);
  std::vector<Claim> claims;
  for (const auto& id : kStudyClaims) {
    if (id.starts_with("C4") || id.starts_with("C5")) {
      claims.push_back(judge_compliance(id, runs));
      continue;
    }
    Claim c;
    if (id == "C1") c = claim_c1(peaks);
    if (id == "C2") c = claim_c2(peaks);
    if (id == "C3") c = claim_c3(peaks);
    bool all_ok = true;
    for (const auto& name : kClaimRuns.at(id)) {
      const RunRow* r = get(name);
      c.runs.push_back(name);
      if (r == nullptr || !r->ok()) {
        all_ok = false;
        c.failure += (c.failure.empty() ? "" : "; ") + name + ": " +
                     (r == nullptr ? std::string("not run") : r->status);
      }
    }
    if (id == "C6") {
      std::string failure = c.failure;
      const std::vector<std::string> used = c.runs;
      c = claim_c6(all_ok ? sliding_state(*get("exc5"), mu, failure) : SlidingState{}, mu);
      c.failure = failure;
      c.runs = used;
    }
    claims.push_back(std::move(c));
  }
  return claims;
}

double tornado_peak(const Rows& rows, const std::string& point) {
  const auto p = rows.find(point);
  if (p == rows.end()) return std::nan("");
  const auto r = p->second.find(kTornadoRun);
  return r == p->second.end() || !r->second.ok() ? std::nan("") : r->second.peak_theta;
}

}  // namespace nsb::paper_figures::uncertainty

namespace nsb::paper_figures {

Fig6Sweep fig6_sweep(const std::filesystem::path& scenes, const std::filesystem::path& dir,
                     const std::vector<int>& pga_runs, const std::vector<int>& mu0_runs,
                     int workers) {
  namespace u = uncertainty;
  if (workers < 1) throw std::invalid_argument("workers: must be >= 1");
  const std::vector<ClaimRun> runs = fig6_runs(pga_runs, mu0_runs);
  const SceneTargets targets = u::scene_targets(scenes, runs);
  const std::vector<u::Point> nominal{
      {"nominal", nominal_point(), std::vector<std::string>(assumptions().size()), "", ""}};
  const sweep::Design d = u::make_design(
      "fig6", scenes / ("bridge-exc" + std::to_string(u::kBaseExcitation) + ".toml"), nominal,
      targets, 0.0, runs, [](const u::Point&, const ClaimRun&) { return true; });
  Fig6Sweep out;
  const u::Rows rows = u::run_design(d, dir, workers, out.runs, out.failed);
  std::filesystem::remove_all(dir / "runs");
  const auto& point = rows.at("nominal");
  out.peaks = u::peaks_of(point, pga_runs, u::input_pgas(scenes, pga_runs));
  for (const auto& [name, r] : point) out.status[name] = r.status;
  return out;
}

}  // namespace nsb::paper_figures
