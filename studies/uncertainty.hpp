// The uncertainty of the claims' verdicts: the assumed values of the benchmark
// (docs/bridge.md, "Assumed") over their plausible ranges, run through the sweep module
// (sweep/), and the claims C1 ... C6, C4' and C5' judged at every point with the functions of
// paper-figures/claims.hpp, on the claim runs of paper-figures/claim_runs.hpp. Two designs:
//   - one factor at a time (each assumption at the low and the high end of its range, the
//     others nominal): the tornado chart of run 7's peak rotation and the verdicts that flip;
//   - a Latin hypercube over all assumptions at once: the share of the plausible space in
//     which each claim holds.
// The ranges and their reasons, the outputs and the run times: docs/paper-figures.md,
// "Uncertainty of the verdicts".
#pragma once

#include "paper-figures/claim_runs.hpp"
#include "paper-figures/claims.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace nsb::studies {

// The study speaks the figures' vocabulary: their claims, and the claim runs at a point of the
// assumed values (paper-figures/claim_runs.hpp).
using paper_figures::Assumption;
using paper_figures::assumptions;
using paper_figures::Claim;
using paper_figures::ClaimRun;
using paper_figures::nominal_point;
using paper_figures::point_overrides;
using paper_figures::SceneTargets;

// The runs of the study at every point. The set is that of --quick's Fig. 6: runs 1, 3, 5, 7
// with and without pounding, and runs 5 and 7 with mu = 0 (C1, C2, C3), C6 on run 5 with
// pounding, and run 5 under the compliance method at the stiffness factors of C4's checks under
// both compared laws (C4, C4'). C5's runs of the first pounding follow from each point's run 5
// (uncertainty_compliance.cpp).
const std::vector<ClaimRun>& claim_runs();

// ---------------------------------------------------------------------------------------------
// Pure logic: shares and flips.

enum class Verdict { kHolds, kFails, kNotEvaluated };
Verdict verdict_of(const Claim& c);  // kNotEvaluated when a run failed
std::string to_string(Verdict v);    // "holds", "fails", "not evaluated"

// The share of evaluated samples in which a claim holds, with the binomial standard error
// sqrt(p (1 - p) / n) of that share. NaN share and error when no sample was evaluated.
struct Share {
  std::size_t evaluated = 0;      // samples with a verdict
  std::size_t holds = 0;          // of which the claim holds
  std::size_t not_evaluated = 0;  // samples whose runs failed
  double share = 0.0;
  double standard_error = 0.0;
};
Share share_of(const std::vector<Verdict>& verdicts);

// A point of the one-at-a-time design: the base point (assumption empty) or one assumption at
// one end of its range, with the verdict of every claim there.
struct OatPoint {
  std::string assumption;                   // Assumption::key; empty for the base point
  std::string end;                          // "low" or "high"; empty for the base point
  double value = 0.0;                       // the assumption's value there
  std::map<std::string, Verdict> verdicts;  // by claim id
};
// A verdict that differs from the base point's.
struct Flip {
  std::string assumption, end;
  double value = 0.0;
  std::string claim;
  Verdict nominal = Verdict::kNotEvaluated, flipped = Verdict::kNotEvaluated;
};
// Every (point, claim) whose verdict is evaluated at the base point and at that point and
// differs, in the order of the points. Throws std::invalid_argument without exactly one base
// point.
std::vector<Flip> find_flips(const std::vector<OatPoint>& points);

// ---------------------------------------------------------------------------------------------
// The study.

struct UncertaintyOptions {
  std::filesystem::path out;     // the figures' folder; the sweeps go to out/uncertainty/
  std::filesystem::path scenes;  // folder of the scenes (bridge-exc*.toml)
  bool quick = false;            // the tornado on run 7 and 2 samples over 20 s, no flip table
  int workers = 2;               // runs in parallel, >= 1
  std::size_t samples = 0;       // hypercube samples; 0: 24 (full) or 2 (quick)
  std::uint64_t seed = 2017;     // the hypercube's seed
  void validate() const;         // throws std::invalid_argument naming the field
};

struct UncertaintyResult {
  std::vector<std::string> claims;         // the claims judged: C1 ... C6, C4', C5'
  std::map<std::string, Verdict> nominal;  // their verdicts at the nominal point
  std::map<std::string, Share> shares;     // over the hypercube
  std::size_t samples = 0;                 // hypercube samples
  std::vector<OatPoint> oat;               // the one-at-a-time points judged (full set)
  std::vector<Flip> flips;
  // Run 7's peak rotation at the two ends of each range [rad], in the tornado chart's order
  // (largest swing first; the chart's bars also span the nominal value).
  struct TornadoEnds {
    std::string assumption;  // Assumption::key
    double low_end = 0.0, high_end = 0.0;
  };
  std::vector<TornadoEnds> tornado;
  double tornado_base = 0.0;  // run 7's peak rotation at the nominal point [rad]
  int runs = 0;               // integrations
  // Runs that did not complete, "<design> <run> (<point>, <run name>): <status>". A run that
  // fails at some point of the plausible space is an outcome of the study, not an error of the
  // figures: its claims are "not evaluated" there.
  std::vector<std::string> failed;
  std::vector<std::string> plot_errors;
  double wall_time = 0.0;  // [s]
};

// Runs the designs and writes into options.out: uncertainty-tornado.{png,svg,csv},
// uncertainty.csv (one row per hypercube sample: the values, each claim's verdict and the
// quantities of its checks), uncertainty-oat.csv (the same per one-at-a-time point),
// uncertainty.json and uncertainty.md. Throws std::invalid_argument for bad options.
UncertaintyResult run_uncertainty(const UncertaintyOptions& options);

// uncertainty.json and uncertainty.md from a result.
std::string uncertainty_json(const UncertaintyResult& r);
std::string uncertainty_markdown(const UncertaintyResult& r, bool quick);

}  // namespace nsb::studies
