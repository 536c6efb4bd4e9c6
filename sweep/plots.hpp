// Plots of a sweep's results (those of results.csv, sweep/results.hpp), drawn with gnuplot into DIR/plots/ as PNG and SVG, each
// beside the CSV it is drawn from (docs/sweep.md):
//   ida.{csv,gp,png,svg}         incremental dynamic analysis: the response against the PGA,
//                                one curve per combination of the other factors (record, mu)
//   exceedance.{csv,gp,png,svg}  share of the runs whose response exceeds a limit, against PGA
//   tornado.{csv,gp,png,svg}     one factor at a time: each factor's swing of the response
//                                about the base run
// Runs that did not complete are left out of every plot (results.csv keeps them). A run that
// stopped at the loss of a seat (status "unseated", a result: docs/limit-states.md) is drawn in
// the IDA plot as a point of its own, at its response up to the loss of seat, off the curves,
// and counts as exceeding the limit in the exceedance plot (the collapse convention of the
// fragility curves, sweep/limit_states.hpp); the tornado chart leaves it out.
#pragma once

#include "sweep/results.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace nsb::sweep {

struct PlotOptions {
  std::string pga_key = "model.excitation.target_pga";  // the factor on the x axis [g]
  std::string response = "peak_theta";  // the results.csv column plotted [rad for peak_theta];
                                        //   peak_theta1 when only a segmented bridge's exist
  double limit = 0.01;                  // exceedance threshold, in the response's unit, > 0
  std::string gnuplot = "gnuplot";      // gnuplot executable (on PATH, or a path), non-empty
  void validate() const;                // throws std::invalid_argument naming the field
};

struct IdaPoint {
  std::string curve;  // the other factors' values, "key=value; ..." ("all" when none)
  double pga = 0.0;   // [g]
  double response = 0.0;
  bool unseated = false;  // the run stopped at the loss of a seat: response up to that instant
};
// One point per completed or unseated run that has a PGA, sorted by curve then PGA. Empty
// when results.csv has no column named options.pga_key.
std::vector<IdaPoint> ida_points(const Results& results, const PlotOptions& options);

struct ExceedancePoint {
  double pga = 0.0;           // [g]
  std::size_t runs = 0;       // completed and unseated runs at this PGA
  std::size_t exceeding = 0;  // of which response > limit, or unseated
  std::size_t unseated = 0;   // of runs: unseated (each counted as exceeding)
  double share = 0.0;         // exceeding / runs
};
std::vector<ExceedancePoint> exceedance_points(const Results& results, const PlotOptions& options);

struct TornadoBar {
  std::string factor;
  double low = 0.0, high = 0.0;  // least and largest response over the factor's levels
  std::string low_level, high_level;
  double base = 0.0;  // response of the base run
};
// For a one-factor-at-a-time design: the base run is the row whose factor columns are all
// empty; a factor's bar spans the runs that set that factor alone. Sorted by swing
// (high - low), largest first. Empty when there is no base run.
std::vector<TornadoBar> tornado_bars(const Results& results, const PlotOptions& options);

// Writes every plot that the results support into dir and runs gnuplot on each script.
// Returns the files written. Throws std::invalid_argument for bad options or results
// without the response column, std::runtime_error when gnuplot fails.
std::vector<std::filesystem::path> draw_plots(const Results& results,
                                              const std::filesystem::path& dir,
                                              const PlotOptions& options);

}  // namespace nsb::sweep
