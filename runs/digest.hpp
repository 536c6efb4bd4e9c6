// What a run's history says in a few numbers, computed once after the run and read by every
// caller: summary.json's "peaks", "events", "contact_events" and "input", the sweep's
// results.csv row, the terminal summary of `nsbridge run`, and the trust checks
// (runs/trust.hpp).
#pragma once

#include "integrators/recorder.hpp"
#include "models/excitation_scaling.hpp"

#include <array>
#include <cstdint>
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
};

// A generalized coordinate's largest magnitude and its last recorded value.
struct CoordinatePeak {
  std::string name;       // the system's name of the coordinate ("x", "theta", ...)
  double peak = 0.0;      // max |q| over the samples, NaN samples skipped [unit of q]
  double residual = 0.0;  // q at the last sample; both NaN without samples
};

// Event counts of one contact, per kind in the order of integrators::kEventKindNames.
struct ContactEvents {
  int contact = 0;  // 1-based
  std::array<std::int64_t, integrators::kEventKindNames.size()> counts{};
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

  std::int64_t count(integrators::EventKind kind) const;  // events of a kind, in total
};

// The digest of a finished run, without the trust checks' warnings (runs::execute adds them),
// with the system's limit states after the run.
Digest make_digest(const integrators::Recorder& history, const integrators::RunResult& result,
                   std::vector<integrators::LimitStateValue> limit_states = {});

// The peak entry of a column name; nullptr when the history has no such column.
const ColumnPeak* find_peak(const Digest& digest, const std::string& column);

}  // namespace nsb::runs
