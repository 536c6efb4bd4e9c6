#include "paper-figures/figures.hpp"

#include "io/files.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>

#include "paper-figures/figure.hpp"

#ifndef NSB_SCENES_DIR
#error "NSB_SCENES_DIR must name the scenes folder (set by paper-figures/CMakeLists.txt)"
#endif

namespace nsb::paper_figures {

namespace fs = std::filesystem;

void FigureOptions::validate() const {
  if (out.empty()) throw std::invalid_argument("out: an output folder is required");
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec)) {
    throw std::invalid_argument("out: \"" + out.string() + "\" exists and is not a folder");
  }
  if (!scenes.empty() && !fs::is_directory(scenes, ec)) {
    throw std::invalid_argument("scenes: \"" + scenes.string() + "\" is not a folder");
  }
  if (gnuplot.empty()) throw std::invalid_argument("gnuplot: the executable must be named");
  if (workers < 1 || workers > 64) throw std::invalid_argument("workers: must be in [1, 64]");
}

double input_pga(const scene::Scene& scene, bool transverse) {
  if (!scene.design || scene.design->excitation.bents.empty()) return 0.0;
  const auto& bent = scene.design->excitation.bents[0];
  const auto& m = transverse ? bent.transverse : bent.longitudinal;
  return m ? m->pga() / 9.81 : 0.0;
}

namespace {

// The runs that the figures' `runs` (follow_up = false) or `follow_up` entries ask for, each
// once: several figures share a run (excitation 5 under Moreau-Jean).
std::vector<RunSpec> runs_asked(const Study& s, bool follow_up) {
  std::vector<RunSpec> specs;
  for (const auto& f : registered_figures()) {
    const auto& ask = follow_up ? f.follow_up : f.runs;
    if (!ask) continue;
    for (auto& r : ask(s)) {
      const auto same = std::find_if(specs.begin(), specs.end(),
                                     [&](const RunSpec& x) { return x.name == r.name; });
      if (same == specs.end()) {
        specs.push_back(std::move(r));
      } else if (same->scene != r.scene || same->overrides != r.overrides) {
        throw std::logic_error("paper-figures: two different runs named " + r.name);
      }
    }
  }
  return specs;
}

// Makes the runs of every figure, in two rounds (the follow-up runs are placed by the first
// runs' events), into out/figure-runs/, and records the ones that failed.
void make_figure_runs(Study& s, const FigureOptions& options, FigureResult& res) {
  const fs::path dir = options.out / "figure-runs";
  for (bool follow_up : {false, true}) {
    const std::vector<RunSpec> specs = runs_asked(s, follow_up);
    const fs::path round = dir / (follow_up ? "follow-up" : "first");
    for (auto& r : make_runs(specs, s.scenes, round, options.workers)) {
      if (!r.ok()) res.failed.push_back(r.status_text());
      s.runs.add(std::move(r));
    }
    res.runs += static_cast<int>(specs.size());
  }
}

void write_claims(const fs::path& dir, const std::vector<Claim>& claims) {
  io::write_file_atomically(dir / "claims.json", claims_json(claims));
  io::write_file_atomically(
      dir / "claims.md",
      claims_markdown(claims) +
          "\nHow far the verdicts depend on the assumed values: uncertainty.md (shares over a "
         "Latin hypercube, verdicts that one assumption flips, tornado chart of run 7).\n");
}

}  // namespace

FigureResult make_figures(const FigureOptions& options) {
  options.validate();
  const auto t0 = std::chrono::steady_clock::now();
  Study s;
  s.setup = make_setup(options.quick);
  s.scenes = options.scenes.empty() ? fs::path(NSB_SCENES_DIR) : options.scenes;
  FigureResult res;
  res.scenes = s.scenes;
  make_figure_runs(s, options, res);

  // Fig. 6 and C1-C3: one sweep over the runs with and without pounding and with mu = 0.
  s.fig6 = fig6_sweep(s.scenes, options.out / "fig6-sweep", s.setup.pga_runs, s.setup.mu0_runs,
                      options.workers);
  res.runs += s.fig6.runs;
  res.failed.insert(res.failed.end(), s.fig6.failed.begin(), s.fig6.failed.end());

  const Canvas canvas{options.out, options.gnuplot};
  for (const auto& f : registered_figures()) {
    const Drawing d = f.draw(s, canvas);
    if (d.files.empty()) continue;
    res.figures.push_back(f.name);
    if (!d.error.empty()) res.plot_errors.push_back(d.error);
  }
  res.claims = nominal_claims(s);
  write_claims(options.out, res.claims);

  res.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace nsb::paper_figures
