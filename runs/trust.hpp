// Whether a run can be trusted: checks of the input before a run, and of the result after it.
// Thresholds and their derivation: docs/cli.md, "Warnings".
//
// Each warning is one line "<code>: <what was found>; <what the method needs>", with <code>
// one of energy_balance, penetration, restitution, step_period, step_record. runs::execute appends them to
// RunResult::warnings and Digest::warnings (summary.json "warnings"), for `nsbridge run` and
// every run of a sweep alike; `nsbridge run` prints them and with --strict exits 1 on any.
#pragma once

#include "integrators/recorder.hpp"
#include "integrators/run.hpp"
#include "integrators/system.hpp"
#include "runs/digest.hpp"

#include <string>
#include <vector>

namespace nsb::runs {

struct TrustLimits {
  // Largest relative energy-balance error EnergyBalance::error accepted, in (0, 1).
  double energy_error = 0.01;
  // Largest penetration accepted, as a fraction of the contact's range of gaps over the run
  // (max g_N - min g_N), in (0, 1).
  double penetration = 0.01;
  // Largest penetration of a compliance contact accepted, as a fraction of its gap at t0 (its
  // opening at rest), in (0, 1): beyond it the contact's deformation is a sizeable share of
  // the free play that the rigid methods keep, and the stiffness is too soft for the bridge
  // (docs/compliance.md, "Contact laws per family").
  double compliance_penetration = 0.5;
  // Fewest Moreau–Jean steps per shortest natural period of the system, >= 1.
  double steps_per_period = 20.0;
  // Largest Moreau–Jean step as a multiple of the record's sampling interval, > 0.
  double record_steps = 1.0;
  // Largest difference between the restitution a compliance contact is given and the one its
  // damping law returns from a single impact (integrators::hunt_crossley_restitution), in
  // (0, 1): 0.05 lets hertzdamp pass from e = 0.8 (0.847) and warns at the paper's e = 0
  // (0.663) and at 0.5 (0.725) (docs/compliance.md, "Damping laws").
  double restitution_mismatch = 0.05;
  void validate() const;  // throws std::invalid_argument naming the field
};

// The shortest natural period 2 pi / omega_max [s] of the undamped linearization at the
// initial state: omega^2 are the eigenvalues of K phi = omega^2 M phi, with K the symmetric
// part of the tangent stiffness at t0. Infinite when K has no positive eigenvalue.
// Evaluates the system's tangent at its initial state and reverts the trial state.
double shortest_period(integrators::System& system);

// Throws std::invalid_argument when the initial state makes the energy (1/2 u^T M u, or the
// stored energy) non-finite: values that overflow the computation are bad input.
void check_initial_state(const integrators::System& system);

// Warnings about the configuration, before the run: the Moreau–Jean step against the shortest
// period and the record's sampling interval (record_step [s], 0 without a record); under the
// compliance method, each restitution that its damping law does not return (code
// restitution), with the contacts that have it.
std::vector<std::string> step_warnings(integrators::System& system,
                                       const integrators::RunConfig& config, double record_step,
                                       const TrustLimits& limits = {});

// Warnings about a finished run from its digest: its error estimate against solver.accuracy
// (runs/estimate.hpp, accuracy_warning), its energy-balance error and the deepest
// penetration of each contact (its gap columns, by ColumnKind): for the rigid-contact methods
// against its range of gaps (a numerical violation of g_N >= 0); for compliance, whose
// penetration is the modelled contact deformation, against its gap at t0.
std::vector<std::string> result_warnings(const integrators::Recorder& history,
                                         const Digest& digest,
                                         const integrators::RunResult& result,
                                         const TrustLimits& limits = {});

}  // namespace nsb::runs
