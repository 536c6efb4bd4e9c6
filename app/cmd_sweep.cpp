// nsbridge sweep DESIGN.toml --out DIR [--jobs N] [--set key=value ...] [--restart] [--hdf5]
//                            [--plot [--pga-key KEY] [--response COLUMN] [--limit VALUE]
//                                    [--gnuplot PATH]] [--plot-only]
//
// Expands a design file (docs/sweep.md) into runs of one scene, runs them on --jobs threads
// (or, started by mpirun, on every rank), writes each run's outputs to DIR/runs/<id>/ and one
// row per run to DIR/results.csv (with --hdf5 also into DIR/sweep.h5, docs/outputs.md). A
// rerun over the same DIR resumes. A design with a
// [fragility] section also gets DIR/fragility.json (and, with --plot, DIR/fragility.png):
// docs/fragility.md. Exit code 1 when some run did not complete (the rows say which); 2 for a
// bad design, before any run, or for a DIR that cannot be written, before or during the runs
// (a full disk: the runs complete so far stay, and a rerun resumes). Ctrl-C stops the runs
// under way, which write nothing, and exits 130; a rerun resumes.
#include "app/commands.hpp"
#include "app/interrupt.hpp"
#include "io/files.hpp"

#include "store/study_store.hpp"
#include "sweep/fragility_sweep.hpp"
#include "sweep/plots.hpp"
#include "sweep/runner.hpp"

#include <iostream>
#include <limits>
#include <memory>
#include <string>

namespace nsb::app {

namespace {

struct SweepArgs {
  std::string design;
  sweep::SweepOptions options;
  bool plot = false;
  bool plot_only = false;
  bool hdf5 = false;
  sweep::PlotOptions plots;
};

void draw(const SweepArgs& args, const sweep::Results& results) {
  const auto files = sweep::draw_plots(results, args.options.out / "plots", args.plots);
  std::cout << "plots      "
            << (files.empty() ? "none (no PGA factor and no base run)"
                              : (args.options.out / "plots").string() + "/")
            << '\n';
}

// The fragility curves of a design with [fragility], fitted to the sweep's results.
void fragility(const SweepArgs& args, const sweep::Design& d, const sweep::Results& results,
               bool plot) {
  const auto files = sweep::write_fragility(d, results, args.options.out,
                                            plot ? args.plots.gnuplot : std::string());
  for (const auto& f : files) std::cout << "fragility  " << f.string() << '\n';
}

void sweep_and_report(SweepArgs& args) {
  args.plots.validate();
  if (args.plot_only) {
    // The results of an earlier process: read back from the results.csv it wrote.
    const sweep::Results results =
        sweep::results_of(sweep::read_csv(args.options.out / "results.csv"));
    draw(args, results);
    fragility(args, sweep::load_design(args.design, args.options.set), results, true);
    return;
  }
  args.options.stop = &stop_on_interrupt();
  std::unique_ptr<store::StudyStore> h5;
  if (args.hdf5) {
    h5 = std::make_unique<store::StudyStore>(args.options.out, args.options.restart);
    args.options.observer = h5.get();
  }
  const sweep::SweepSummary s = sweep::run_sweep(args.design, args.options);
  if (!s.primary) return;
  if (h5)
    for (const auto& note : h5->notes()) std::cerr << "nsbridge sweep: " << note << '\n';
  if (s.interrupted) {
    std::cerr << "nsbridge sweep: interrupted: " << s.complete << " of " << s.runs
              << " runs complete in " << args.options.out.string()
              << "; the same command resumes the sweep\n";
    exit_code() = kInterruptedExit;
    return;
  }
  for (const auto& note : s.notes) std::cerr << "nsbridge sweep: " << note << '\n';
  std::cout << "runs       " << s.runs << " in the design; " << s.already_done
            << " already done (skipped), " << s.ran << " run now\n";
  std::cout << "workers    " << s.workers << " thread" << (s.workers == 1 ? "" : "s") << " on "
            << s.ranks << " process" << (s.ranks == 1 ? "" : "es")
            << (sweep::mpi_built_in() ? " (MPI built in)" : " (MPI is not built in)");
  if (s.ranks > 1) std::cout << "; " << s.ran_elsewhere << " runs on ranks other than 0";
  std::cout << '\n';
  std::cout << "failed     " << s.failed << " of " << s.runs
            << " runs did not complete (their status is in results.csv)\n";
  std::cout << "results    " << s.results.string() << '\n';
  if (h5) std::cout << "store      " << h5->file().string() << '\n';
  if (args.plot) draw(args, s.table);
  fragility(args, s.design, s.table, args.plot);
  if (s.failed > 0) exit_code() = 1;
}

void run(SweepArgs& args) {
  try {
    sweep_and_report(args);
  } catch (const io::WriteError& e) {
    // A full disk, a quota or a lost permission while the sweep wrote: as an --out that could
    // not be written at all. The runs written completely are kept; a rerun resumes.
    throw InputError("--out " + args.options.out.string() + ": " + e.what());
  }
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  auto* cmd = app.add_subcommand(
      "sweep", "Run every run of a design file (grid, latin, list, oat) on all cores or MPI ranks");
  cmd->add_option("design", args->design, "Design file (TOML, docs/sweep.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", args->options.out, "Folder of the sweep: runs/<id>/, results.csv")
      ->required();
  cmd->add_option("--jobs", args->options.jobs, "Worker threads per process (0 = all cores)")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  cmd->add_option("--set", args->options.set,
                  "Add an override to every run, e.g. --set solver.end_time=2 (repeatable)")
      ->allow_extra_args(false);
  cmd->add_flag("--restart", args->options.restart,
                "Discard the runs already in --out (needed when the design changed)");
  cmd->add_flag("--hdf5", args->hdf5,
                "Also write DIR/sweep.h5: every run's history, events, summary and the results "
                "(docs/outputs.md)");
  cmd->add_flag("--plot", args->plot,
                "Draw IDA, exceedance and tornado plots into DIR/plots/ (and DIR/fragility.png)");
  cmd->add_flag("--plot-only", args->plot_only, "Only draw the plots from DIR/results.csv");
  cmd->add_option("--pga-key", args->plots.pga_key,
                  "Factor on the x axis of the IDA and "
                  "exceedance plots [g]")
      ->capture_default_str();
  cmd->add_option("--response", args->plots.response, "results.csv column to plot")
      ->capture_default_str();
  cmd->add_option("--limit", args->plots.limit, "Exceedance limit of the response [rad]")
      ->capture_default_str();
  cmd->add_option("--gnuplot", args->plots.gnuplot, "gnuplot executable (on PATH or a path)")
      ->capture_default_str();
  cmd->callback([args] { run(*args); });
}

}  // namespace nsb::app
