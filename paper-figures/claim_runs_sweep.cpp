// The claim runs through the sweep runner: a design run into a folder, its rows typed in
// memory, Fig. 6's peaks from the rows of one point, and Fig. 6's sweep at the nominal point.
#include <algorithm>
#include <stdexcept>

#include "paper-figures/claim_runs.hpp"
#include "paper-figures/figures.hpp"
#include "scene/scene.hpp"
#include "sweep/runner.hpp"

namespace nsb::paper_figures {

namespace fs = std::filesystem;

bool RunRow::ok() const {
  const auto s = integrators::parse_run_status(status);
  return s && integrators::succeeded(*s);
}

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
                    peak = t.column("peak_theta"), impacts = t.column("impacts"),
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

InputPga input_pgas(const fs::path& scenes, const std::vector<int>& excitations) {
  InputPga pga;
  for (int n : excitations) {
    const auto scene = scene::load_scene(scenes / ("bridge-exc" + std::to_string(n) + ".toml"));
    pga[n] = {input_pga(scene, true), input_pga(scene, false)};
  }
  return pga;
}

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

Fig6Sweep fig6_sweep(const std::filesystem::path& scenes, const std::filesystem::path& dir,
                     const std::vector<int>& pga_runs, const std::vector<int>& mu0_runs,
                     int workers) {
  if (workers < 1) throw std::invalid_argument("workers: must be >= 1");
  const std::vector<ClaimRun> runs = fig6_runs(pga_runs, mu0_runs);
  const SceneTargets targets = scene_targets(scenes, runs);
  const std::vector<Point> nominal{
      {"nominal", nominal_point(), std::vector<std::string>(assumptions().size()), "", ""}};
  const sweep::Design d = make_design(
      "fig6", scenes / ("bridge-exc" + std::to_string(kBaseExcitation) + ".toml"), nominal,
      targets, 0.0, runs, [](const Point&, const ClaimRun&) { return true; });
  Fig6Sweep out;
  const Rows rows = run_design(d, dir, workers, out.runs, out.failed);
  std::filesystem::remove_all(dir / "runs");
  const auto& point = rows.at("nominal");
  out.peaks = peaks_of(point, pga_runs, input_pgas(scenes, pga_runs));
  for (const auto& [name, r] : point) out.status[name] = r.status;
  return out;
}

}  // namespace nsb::paper_figures
