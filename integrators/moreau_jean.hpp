// The theta-method Moreau–Jean time-stepping scheme (Jean 1999; Acary & Brogliato 2008,
// Numerical Methods for Nonsmooth Dynamical Systems, ch. 10).
//
// On a step [t_k, t_k+1] of size h, with f_k = f(t_k, q_k, u_k) and the tangent K, C of the
// committed state, the smooth force is linearised about (q_k, u_k) (Acary & Brogliato, ch. 10):
//
//   A (u_k+1 - u_k) = h [(1 - theta) f_k + theta f(t_k+1, q_k, u_k)] - h^2 theta K u_k
//                     + W_N Lambda_N + W_T Lambda_T,          A = M + h theta C + h^2 theta^2 K
//   q_k+1 = q_k + h [(1 - theta) u_k + theta u_k+1]
//
// so that u_k+1 = u_free + A^-1 (W_N Lambda_N + W_T Lambda_T). The contacts taking part in
// the step are those with g_N + (h/2) gdot_N <= 0 at t_k (closed, or predicted to close
// within the step). Over that index set one velocity-level frictional problem is solved
// (lcp/frictional.hpp, eq. 6 of Shi & Dimitrakopoulos 2017) with the Delassus matrix
// G = W^T A^-1 W, the free velocities W^T u_free + what and Newton's law applied to the
// start-of-step normal velocity W_N^T u_k + what_N. The contact forces written to the
// history are lambda = Lambda / h.
//
// See docs/moreau-jean.md for the derivation, the energy balance and what is skipped.
#pragma once

#include "integrators/recorder.hpp"
#include "integrators/run_hooks.hpp"
#include "integrators/system.hpp"
#include "lcp/solve.hpp"

#include <span>
#include <string_view>


namespace nsb::integrators {

// The scheme's state at the end of an accepted step, from which a run continues as the run
// that saved it would have, given the system in its state of that step (e.g. a copy of a
// models::Assembly taken there): the time and q, u; the origin of the step grid
// t_k = grid_origin + k h, on which `time` lies (t_b + k h and grid_origin + (K + k) h differ
// by round-off, and the ground motions are read at t_k); the energy balance accumulated since
// the saving run's t0; and the tangent K, C the iteration matrix A was built with (re-evaluated
// only when the system reports a change beyond its own tolerance, e.g. a Takeda spring's, so
// an evaluation at `time` may differ from it). Everything else carried from step to step is
// evaluated again from these and the system's committed state, as at any start: f_k, A^-1,
// the contact data and the powers at t_k. The previous step's impulses enter only the
// history's force columns at `time` itself; the contact problem keeps no warm start. See
// docs/moreau-jean.md, "Restarting a run".
struct MoreauJeanCheckpoint {
  double time = 0.0;          // [s]
  Vector position, velocity;  // q [m, rad], u [m/s, rad/s] at `time`
  double grid_origin = 0.0;   // [s]
  EnergyBalance energy;       // [kJ], since the saving run's t0
  Matrix stiffness, damping;  // K, C of the iteration matrix at `time` [kN/m, kN s/m]
};

struct MoreauJeanOptions {
  static constexpr std::string_view kMethod = "moreau";  // solver.method in scene files
  double end_time = 1.0;       // final time [s], > initial time of the system
  double step = 1e-4;          // time step h [s], > 0; the last step is shortened to end_time
  double theta = 0.5;          // theta of the theta-method, in [0.5, 1]
  lcp::Solver solver = lcp::Solver::kLemke;  // solver of the contact problem of each step
  double lcp_tolerance = 1e-12;  // lcp::SolveOptions::tolerance, > 0
  bool lcp_fallback = true;    // run the contact stage's fallback chain (Lemke, PGS,
                               //   enumeration) when the chosen solver fails
  // Normal or tangential contact velocity [m/s] below which a contact counts as resting or
  // sticking, for events only (it does not change the dynamics); > 0.
  double event_velocity_tolerance = 1e-6;
  // Adaptive steps (docs/moreau-jean.md, "Adaptive steps"). 0: every step is `step`. > 0:
  // each step is chosen so that the local error estimate of every coordinate is at most
  // local_tolerance times its scale (its peak so far), `step` being the first trial step; a
  // step in which a contact impacts or changes state is retried smaller, down to min_step.
  double local_tolerance = 0.0;  // relative local error of q per step [-], in [0, 1)
  double min_step = 1e-6;        // smallest adaptive step [s], > 0
  double max_step = 0.0;         // largest adaptive step [s], >= 0; 0: 10 x step
  // The schema of these fields (keys of a scene's [solver] table, units, ranges).
  static std::span<const config::Field<MoreauJeanOptions>> fields();
  void validate() const;       // throws std::invalid_argument naming the key
};

// Integrates system from its initial state to options.end_time. Samples the history into
// recorder (contact forces lambda = Lambda / h) and records per-contact events; calls
// progress (may be empty) every few thousand steps; hooks (run_hooks.hpp) may show every
// contact problem to an observer, resume from a checkpoint and save one at the end. Throws std::invalid_argument for bad
// options or a system whose sizes are inconsistent; every numerical outcome is the
// RunResult's status: kDiverged (a non-finite force, state, contact problem or energy; the
// run stops), kContactUnsolved (a problem no solver of the chain solved; the run goes on with
// the best answer), kCompletedWithFallbacks, kCompleted.
RunResult moreau_jean(System& system, const MoreauJeanOptions& options, Recorder& recorder,
                      const Progress& progress = {}, const RunHooks& hooks = {});
// solver.adapt = true under Moreau–Jean: the local tolerance a run starts from when the scene
// gives none, as a multiple of solver.accuracy (docs/moreau-jean.md, "Adaptive steps": the
// local errors of the thousands of steps of a record add up, mostly as a phase error, so the
// tolerance per step is a hundredth of the relative accuracy asked of the peaks).
inline constexpr double kLocalToleranceOfAccuracy = 0.01;

// The run API's entry for this method (integrators/run.hpp).
inline RunResult run_method(System& system, const MoreauJeanOptions& options, Recorder& recorder,
                            const Progress& progress, const RunHooks& hooks) {
  return moreau_jean(system, options, recorder, progress, hooks);
}

}  // namespace nsb::integrators
