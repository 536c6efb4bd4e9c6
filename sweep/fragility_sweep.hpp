// Fragility curves from a sweep (docs/fragility.md, "Fragility from a sweep"): the design's
// `[fragility]` section names the factor whose levels are the intensity stripes and the limit
// states; after the runs, every limit state is fitted to results.csv by maximum likelihood
// over the stripes (sweep/fragility.hpp, fit_mle), and, for an IDA design, by the method of
// moments on each record's capacity (fit_moments). The results go to DIR/fragility.json and,
// with a gnuplot, DIR/fragility.png.
//
// Which runs count: a run that did not complete (a status other than completed,
// completed_with_fallbacks or unseated, or "rejected") has no trustworthy peak, so it is left
// out of its stripe's n and reported in the stripe's "left_out" count. An unseated run (the
// bridge lost a seat and the run stopped there) is a result: it counts in n, and reaches
// every limit state unless the limit state says `unseated = "response"` (sweep/limit_states.hpp).
// A row without an IM (an empty or non-numeric label) belongs to no stripe and is left out too.
#pragma once

#include "sweep/csv.hpp"
#include "sweep/design.hpp"
#include "sweep/fragility.hpp"
#include "sweep/limit_states.hpp"
#include "sweep/results.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace nsb::sweep {

// Reads and checks the `[fragility]` table of a design whose factors are already expanded
// (load_design calls it): its keys, `im` a factor key of the design whose levels are numbers
// > 0, each limit state's `name` (unique), `response` (a results.csv column of this design:
// result_columns(base_coordinates(d))) and `threshold` (finite). std::nullopt when the design
// has no [fragility]. Throws std::invalid_argument "<file>:<line>:<col>: fragility.<key>: <what
// is allowed>", with file as given.
std::optional<FragilitySpec> read_fragility(const toml::table& root, const Design& d,
                                            const std::string& file);

// A stripe as the sweep counted it: the runs at one IM level.
struct StripeCount {
  double im = 0.0;   // the level [unit of the IM factor]
  int n = 0;         // completed runs at the level
  int exceeded = 0;  // of which reached the limit state
  int unseated = 0;  // of n: runs stopped by the loss of a seat (counted as LimitState says)
  int left_out = 0;  // runs at the level that did not complete (not in n)
};

// The method of moments on IDA capacities (Baker 2015, eqs. 2-3). Each combination of the
// other factors' levels is one record run at every IM level; its capacity is the lowest IM at
// which it reached the limit state. A record that never reached it within the IMs of the
// design is censored: its capacity is unknown, and the moments, which need every capacity,
// are then not computed (status "censored").
struct MomentsFit {
  std::string status;   // a FitStatus name (fit_moments), or "censored"
  std::string message;  // why there is no estimate
  double theta = 0.0;   // [unit of IM]; 0 = not fitted
  double beta = 0.0;    // [-]; 0 = not fitted
  int records = 0;      // records (IDA curves)
  int censored = 0;     // of which never reached the limit state
};

struct LimitStateFit {
  LimitState limit;
  std::vector<StripeCount> stripes;  // every IM level of the design, ascending
  FragilityFit mle;                  // fit_mle over the stripes with n > 0
  std::optional<MomentsFit> moments;  // IDA designs only
};

struct FragilityReport {
  std::string im;                    // the IM factor's key
  std::vector<LimitStateFit> fits;   // in the design's order
};

// True when the design is an incremental dynamic analysis in the IM: a grid with the IM
// factor at two or more levels and at least one other factor (every combination of the
// others, a record, is run at every IM level).
bool is_ida(const Design& d, const std::string& im);

// Fits every limit state of spec to the rows of results (results.csv's table). ida: also fit the
// moments on the IDA capacities. Throws std::invalid_argument when results lacks the IM or a
// response column; every numerical outcome is a status.
FragilityReport fit_fragility(const FragilitySpec& spec, const Results& results, bool ida,
                              const FitOptions& options = {});

// fragility.json: {"im", "limit_states": {name: {"response", "threshold", "absolute",
// "status", "message", "theta", "beta", "ci95_theta", "ci95_beta", "stripes": [{"im", "n",
// "exceeded", "left_out"}], "moments"}}}; theta, beta and the bands null without an estimate,
// the bands null when not computed, "moments" null for a design that is not an IDA.
std::string fragility_json(const FragilityReport& report);

// The gnuplot script (without terminal and output) of the fitted curves, their bootstrap
// bands and the stripes' observed fractions, the data inline.
std::string fragility_script(const FragilityReport& report);

// For a design with [fragility]: fits the sweep's results (those of DIR/results.csv), writes
// DIR/fragility.json and, when gnuplot is not empty, draws DIR/fragility.png with it. Returns
// the files written (none for a design without [fragility]). Throws std::invalid_argument when
// results lack a column the fit reads, std::runtime_error when gnuplot fails.
std::vector<std::filesystem::path> write_fragility(const Design& d, const Results& results,
                                                   const std::filesystem::path& out,
                                                   const std::string& gnuplot);

}  // namespace nsb::sweep
