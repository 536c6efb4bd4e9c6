// The figure of a run folder (history.csv, events.csv, summary.json as `nsbridge run` writes
// them, docs/outputs.md), drawn by gnuplot (io::draw_gnuplot) for any scene: its bodies
// (x<b>, y<b>, theta<b>), its contacts grouped by family (summary.json "contacts": abutments,
// hinges, shear keys), its bents' hysteresis (bent<i>_ux, bent<i>_fx, ...), its energy and
// its events, titled with the method the run used (summary.json "method"). docs/plots.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::app {

// What a figure shows (`--what`).
inline const std::vector<std::string>& plot_kinds() {
  static const std::vector<std::string> kinds = {"response", "gaps", "bents", "energy",
                                                 "events"};
  return kinds;
}

// The default picture of a run folder: <run_dir>/<what>.png.
std::filesystem::path default_plot_file(const std::filesystem::path& run_dir,
                                        const std::string& what);

// Draws `what` of the run in run_dir to `out` (.png, .svg or .pdf). The picture is drawn
// under a hidden temporary name beside `out` and renamed into place, so `out` is whole or
// untouched. Throws InputError (exit 2) for bad input, naming the file: a missing folder, a
// missing or garbled history.csv or summary.json (or events.csv for "events"), an unknown
// `what`, an extension other than .png, .svg, .pdf, a run without the columns `what` needs
// (the bents' without [output] groups = ["bents"]). Returns an empty string, or what failed
// when gnuplot could not draw (exit 1; nothing written).
std::string plot_run(const std::filesystem::path& run_dir, const std::string& what,
                     const std::filesystem::path& out);

}  // namespace nsb::app
