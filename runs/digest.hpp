// What a run's history says in a few numbers, computed once after the run and read by every
// caller: summary.json's "peaks", "events", "contact_events" and "input", the sweep's
// results.csv row, the terminal summary of `nsbridge run`, and the trust checks
// (runs/trust.hpp).
#pragma once

#include "integrators/recorder.hpp"
#include "models/excitation_scaling.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace nsb::runs {

// The extremes of one history column over its finite samples, and when they occur (the first
// sample that reaches each). Without a finite sample max = -inf, min = +inf and the times NaN.
struct ColumnPeak {
  std::string column;
  double max = 0.0, t_max = 0.0;          // [unit of the column], [s]
  double min = 0.0, t_min = 0.0;
  double abs_max = 0.0, t_abs_max = 0.0;  // max(|max|, |min|) and its time (max's on a tie)
  // The estimated absolute error of abs_max [unit of the column] (runs/estimate.hpp,
  // docs/error-estimates.md); NaN when not estimated.
  double error = std::numeric_limits<double>::quiet_NaN();
};

// A generalized coordinate's largest magnitude and its last recorded value.
struct CoordinatePeak {
  std::string name;       // the system's name of the coordinate ("x", "theta", ...)
  double peak = 0.0;      // max |q| over the samples, NaN samples skipped [unit of q]
  double residual = 0.0;  // q at the last sample; both NaN without samples
  double error = std::numeric_limits<double>::quiet_NaN();  // estimated absolute error of
                                                            //   peak; NaN: not estimated
};

// An impact of the run at which another contact was closing within the estimated error of
// the two contacts' relative gap: which of the two closes first is not resolved by the run's
// step or tolerance (runs/estimate.hpp, impact_order), so no extrapolation bounds what follows.
struct UnresolvedImpactOrder {
  bool found = false;
  double time = std::numeric_limits<double>::quiet_NaN();  // the run's impact [s]
  int contact = 0;           // the impacting contact, 1-based
  int other = 0;             // the contact closing with it, 1-based
  double separation = 0.0;   // the other's gap minus the impacting one's at the impact [m]
  double uncertainty = 0.0;  // factor |separation - the companion's| [m]
};

// The numerical error estimate of a run (runs/estimate.hpp, docs/error-estimates.md): the run
// is repeated by a companion at a coarser step (Moreau–Jean) or a looser tolerance (the
// adaptive methods), and the difference of each number is extrapolated at the method's
// measured order: error = factor |value - companion's value|, factor = 1 / (r^p - 1).
struct ErrorEstimate {
  bool enabled = false;           // solver.error_estimate
  bool computed = false;          // the companion reached a result and the errors are set
  std::string setting;            // "step" or "tolerance": what the companion changed
  double value = 0.0;             // the run's solver.step [s] or solver.tolerance [-]
  double companion_value = 0.0;   // the companion's
  std::string companion_status;   // the companion's RunStatus name; empty when not run
  double order = 0.0;             // p: the order assumed (the lowest measured, nonsmooth)
  double ratio = 0.0;             // r = companion_value / value
  double factor = 0.0;            // 1 / (r^p - 1)
  std::int64_t impacts = 0;       // impacts of the run
  double impacts_error = std::numeric_limits<double>::quiet_NaN();  // |impacts - companion's|
  double first_impact = std::numeric_limits<double>::quiet_NaN();   // time of the first
                                                                    //   impact [s]; NaN: none
  double first_impact_error = std::numeric_limits<double>::quiet_NaN();  // [s]
  UnresolvedImpactOrder impact_order;  // found: every peak's error is at least the peak
  double run_cpu_seconds = 0.0;        // CPU time of the run's integration [s]
  double companion_cpu_seconds = 0.0;  // CPU time of the companion (build and integration) [s]
};

// The run judged against solver.accuracy: every coordinate's peak error estimate at most
// accuracy times the peak (runs/estimate.hpp).
struct Accuracy {
  double target = 0.0;      // solver.accuracy, relative
  bool judged = false;      // an estimate exists (met is meaningful)
  bool met = false;
  std::string worst;        // the coordinate of the largest relative error
  double worst_relative = std::numeric_limits<double>::quiet_NaN();  // its error / peak
};

// One step or tolerance tried by a run that chooses its own (solver.adapt,
// runs/estimate.hpp): its value, the estimate it gave, and what it cost.
struct AdaptAttempt {
  double value = 0.0;  // solver.step [s] or solver.tolerance [-] of the attempt
  double worst_relative = std::numeric_limits<double>::quiet_NaN();  // its largest estimated
                                                                     //   error / peak; NaN:
                                                                     //   no estimate
  bool met = false;             // worst_relative <= solver.accuracy
  std::string status;           // the attempt's RunStatus name
  double cpu_seconds = 0.0;     // CPU time of the attempt: run and companion [s]
};

// A run that chooses its own step or tolerance to meet solver.accuracy (solver.adapt = true):
// every attempt in order; the record is the last one's.
struct Adaptation {
  bool enabled = false;               // solver.adapt
  std::vector<AdaptAttempt> attempts;
  double cpu_seconds = 0.0;           // the attempts' total [s]
};

// One generalized coordinate's peak under the cross-check's method beside the run's.
struct CrossPeak {
  std::string name;  // the coordinate
  double peak = std::numeric_limits<double>::quiet_NaN();   // the other method's |q|max
  double error = std::numeric_limits<double>::quiet_NaN();  // its estimated error; NaN: none
  double difference = std::numeric_limits<double>::quiet_NaN();  // run's peak - peak
  double allowed = std::numeric_limits<double>::quiet_NaN();     // the run's error + error +
                                                                 //   the floor (NaN errors: 0)
  bool agrees = true;                                            // |difference| <= allowed
};

// The same scene under a second method (runs::RunRequest::cross_check), run through the same
// pipeline, and how far its numbers are from the run's (docs/error-estimates.md,
// "Cross-checks").
struct CrossCheck {
  std::string method;  // the other method; empty: no cross-check
  std::string status;  // its RunStatus name
  bool compared = false;  // the other run is a result and its numbers were compared
  std::vector<CrossPeak> coordinates;  // every generalized coordinate, in order
  std::int64_t impacts = 0;            // its impact count
  double impacts_error = std::numeric_limits<double>::quiet_NaN();
  double first_impact = std::numeric_limits<double>::quiet_NaN();  // [s]; NaN: none
  double first_impact_error = std::numeric_limits<double>::quiet_NaN();
  double impacts_difference = 0.0;  // the run's impact count - the other's
  double first_impact_difference = std::numeric_limits<double>::quiet_NaN();  // [s]
  double floor = 0.0;                  // the relative floor of agreement (solver.accuracy)
  std::vector<std::string> warnings;   // the other run's own warnings
  double cpu_seconds = 0.0;            // its cost: build, run and estimate [s]
};

// Event counts of one contact, per kind in the order of integrators::kEventKindNames.
struct ContactEvents {
  int contact = 0;  // 1-based
  std::array<std::int64_t, integrators::kEventKindNames.size()> counts{};
};

// What contact i is (models::parts::CornerContact's family and name), for the outputs.
struct ContactLabel {
  std::string family;  // "abutment", "hinge" or "shear_key"
  std::string name;    // e.g. "left +W/2", "hinge 1 -W/2", "shear_key_left_plus"
  int face = -1;       // contacts of one face share it: corners of one body on one face of
                       //   one obstacle (the impact-order check, runs/estimate.hpp); not written
};

struct Digest {
  std::vector<ColumnPeak> peaks;             // every history column but t, in column order
  std::vector<CoordinatePeak> coordinates;   // every generalized coordinate, in order
  double max_penetration = 0.0;              // max(0, -g_N) over samples and gap columns [m],
                                             //   a removed contact's after its removal skipped
  // Events in total, per kind in the order of integrators::kEventKindNames.
  std::array<std::int64_t, integrators::kEventKindNames.size()> events{};
  std::vector<ContactEvents> contact_events;  // contacts 1..n: n = the recorded contacts, or
                                              //   the largest contact an event names if larger
  integrators::EnergyBalance energy;          // the run's balance at its end
  // summary.json "warnings": the integrator's (RunResult::warnings), then the trust checks'
  // (runs/trust.hpp); the first integrator_warnings entries are the integrator's.
  std::vector<std::string> warnings;
  std::size_t integrator_warnings = 0;
  // summary.json "limit_states": the system's limit states after the run
  // (System::limit_states(), docs/limit-states.md), which runs::run copies from the system.
  std::vector<integrators::LimitStateValue> limit_states;
  // summary.json "input": the scene's excitation as scaled (scene::Scene::input), which
  // runs::run copies from the scene; empty for a digest of a history alone.
  models::InputMotion input;
  // summary.json "contacts": the family and name of every contact of an assembled model (a
  // bridge, a deck, a deck chain), in contact order, which runs::run copies from the system;
  // empty for the test systems and for a digest of a history alone.
  std::vector<ContactLabel> contacts;
  // summary.json "error_estimate" and "accuracy": set by runs::run (runs/estimate.hpp).
  ErrorEstimate estimate;
  Accuracy accuracy;
  // summary.json "accuracy" "attempts" (solver.adapt) and "cross_check": set by runs::run.
  Adaptation adaptation;
  CrossCheck cross_check;

  std::int64_t count(integrators::EventKind kind) const;  // events of a kind, in total
};

// The digest of a finished run, without the trust checks' warnings (runs::execute adds them),
// with the system's limit states after the run.
Digest make_digest(const integrators::Recorder& history, const integrators::RunResult& result,
                   std::vector<integrators::LimitStateValue> limit_states = {});

// The peak entry of a column name; nullptr when the history has no such column.
const ColumnPeak* find_peak(const Digest& digest, const std::string& column);

}  // namespace nsb::runs
