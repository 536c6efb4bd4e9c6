// nsbridge figures --out DIR [--quick]
//
// Regenerates the paper's figures (PNG and SVG, each with its CSV) and writes claims.json and
// claims.md (paper-figures/, docs/paper-figures.md), then the uncertainty study of the claims'
// verdicts beside them (studies/). Exit code 1 when a run or a plot failed (the claims that
// used a failed run say "not evaluated"); 2 for bad input, and for an --out that cannot be
// written (a full disk: every file written is complete, none is partial).
#include <chrono>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "io/files.hpp"
#include "paper-figures/figures.hpp"
#include "studies/uncertainty.hpp"

namespace nsb::app {

namespace {

paper_figures::FigureResult make(const paper_figures::FigureOptions& o) {
  try {
    return paper_figures::make_figures(o);
  } catch (const io::WriteError& e) {
    throw InputError("--out " + o.out.string() + ": " + e.what());
  }
}

studies::UncertaintyResult study(const studies::UncertaintyOptions& o) {
  try {
    return studies::run_uncertainty(o);
  } catch (const io::WriteError& e) {
    throw InputError("--out " + o.out.string() + ": " + e.what());
  }
}

void run_figures(const paper_figures::FigureOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  auto res = make(o);
  // The uncertainty of the verdicts over the assumed values' ranges, beside the figures. Its
  // failed runs are outcomes at points of the plausible space (the claims there are not
  // evaluated), not failed runs of the figures.
  studies::UncertaintyOptions uo;
  uo.out = o.out;
  uo.scenes = res.scenes;
  uo.quick = o.quick;
  uo.workers = o.workers;
  const studies::UncertaintyResult u = study(uo);
  res.runs += u.runs;
  res.plot_errors.insert(res.plot_errors.end(), u.plot_errors.begin(), u.plot_errors.end());
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "figures    " << res.figures.size() << " in " << o.out.string() << " (" << res.runs
            << " runs, " << wall_time << " s)\n";
  for (const auto& c : res.claims) {
    std::cout << "claim " << c.id << "   " << (c.holds() ? "holds" : "does not hold") << ": "
              << c.reason() << '\n';
  }
  for (const auto& id : u.claims) {
    const auto& sh = u.shares.at(id);
    std::size_t flips = 0;
    for (const auto& f : u.flips) flips += f.claim == id;
    std::cout << "uncertainty " << id << ": holds in " << sh.holds << " of " << sh.evaluated
              << " samples (share " << sh.share << " +- " << sh.standard_error << "), " << flips
              << " one-at-a-time flips\n";
  }
  for (const auto& f : u.failed) {
    std::cout << "uncertainty: run did not complete (its claims are not evaluated there): " << f
              << '\n';
  }
  for (const auto& f : res.failed) std::cout << "failed run " << f << '\n';
  for (const auto& f : res.plot_errors) std::cout << "failed plot " << f << '\n';
  if (!res.succeeded()) {
    std::cout << res.failed.size() << " runs and " << res.plot_errors.size() << " plots failed\n";
    exit_code() = 1;
  }
}

}  // namespace

void add_figures_command(CLI::App& app) {
  auto o = std::make_shared<paper_figures::FigureOptions>();
  auto* cmd = app.add_subcommand("figures", "Regenerate the paper's figures and check its claims");
  cmd->add_option("--out", o->out, "Output folder (figures, CSV, claims.json, claims.md)")
      ->required();
  cmd->add_flag("--quick", o->quick, "The reduced set (fewer runs; under a minute)");
  cmd->add_option("--scenes", o->scenes,
                  "Folder of the scenes (default: the source tree's scenes/)");
  cmd->add_option("--gnuplot", o->gnuplot, "gnuplot executable");
  cmd->add_option("--workers", o->workers, "Runs in parallel, 1..64");
  cmd->callback([o] { run_figures(*o); });
}

}  // namespace nsb::app
