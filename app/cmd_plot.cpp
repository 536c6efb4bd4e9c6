// nsbridge plot RUN_DIR [--what response|gaps|bents|energy|events] [--out FILE]
//
// Draws a figure of a run folder (app/run_plot.hpp, docs/plots.md): by default its response
// to RUN_DIR/response.png; --out FILE chooses the picture and its format by the extension
// (.png, .svg, .pdf). Exit 2 for bad input (a missing folder, a missing or garbled file of
// the run, an unknown --what or extension, a run without the columns asked for), exit 1 when
// gnuplot could not draw; neither leaves a file behind.
#include "app/commands.hpp"
#include "app/run_plot.hpp"

#include <iostream>
#include <memory>
#include <string>

namespace nsb::app {

namespace {

struct PlotArgs {
  std::string run_dir;
  std::string what = "response";
  std::string out;
};

void plot(const PlotArgs& a) {
  if (a.run_dir.empty()) throw InputError("plot: empty RUN_DIR; expected a run's output folder");
  const std::filesystem::path out =
      a.out.empty() ? default_plot_file(a.run_dir, a.what) : std::filesystem::path(a.out);
  const std::string failed = plot_run(a.run_dir, a.what, out);
  if (!failed.empty()) {
    std::cerr << "nsbridge: plot: " << failed << "; no file written\n";
    exit_code() = 1;
    return;
  }
  std::cout << out.string() << '\n';
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto args = std::make_shared<PlotArgs>();
  auto* cmd = app.add_subcommand(
      "plot", "Draw a figure of a run folder (history.csv, events.csv, summary.json) with "
              "gnuplot: its response, gaps, bents' hysteresis, energy or events");
  cmd->add_option("run_dir", args->run_dir, "The run's output folder (nsbridge run --out)")
      ->required();
  cmd->add_option("--what", args->what,
                  "response (coordinates and contact forces by family; default), gaps, bents "
                  "(hysteresis loops; needs [output] groups = [\"bents\"]), energy, events")
      ->check(CLI::IsMember(plot_kinds()));
  cmd->add_option("--out", args->out,
                  "The picture: .png, .svg or .pdf (default RUN_DIR/<what>.png)");
  cmd->callback([args] { plot(*args); });
}

}  // namespace nsb::app
