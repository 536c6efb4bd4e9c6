// Event-driven integration of a nonsmooth mechanical system (Pfeiffer & Glocker 1996,
// "Multibody Dynamics with Unilateral Contacts"; Glocker 2001, "Set-Valued Force Laws";
// the approach of Shi & Dimitrakopoulos 2017, §2.2, and their refs. 8–11).
//
// The motion is split into smooth phases and events:
//  - in a smooth phase every contact is in a fixed mode (open, closed and sticking, closed
//    and sliding in a known direction). The constraint forces of the closed contacts follow
//    from the acceleration-level constraints gddot_N = 0 (and gddot_T = 0 when sticking),
//    including the rheonomic terms wbar, and the phase is integrated by Boost.Odeint's
//    Dormand–Prince 5(4) with controlled steps and dense output;
//  - events are located on the dense output by Brent's method (GSL): an open contact
//    closes (g_N = 0 while closing: impact), a closed contact's lambda_N reaches 0
//    (lift-off), a sliding velocity reaches 0 (stick or reversal), a sticking contact's
//    friction force reaches the cone |lambda_T| = mu lambda_N (slip);
//  - an impact is resolved by the frictional impact LCP of eq. (6) with Newton's law;
//    it and the contact LCP below are solved by the contact stage (contact_stage.hpp);
//  - after every event the acceleration-level LCP (the same eq. (6) form with accelerations,
//    eps = 0) decides which touching contacts stay closed and which stick or slide, and
//    positions and velocities of the closed contacts are projected back onto
//    g_N = 0, gdot_N = 0 (and gdot_T = 0 when sticking) to remove drift.
//
// Accumulation of impacts (Zeno): a contact whose post-impact normal velocity is below
// `closing_velocity` is treated as closed. A bound on the number of events per unit time
// guarantees termination; reaching it is reported as a kWarning event.
#pragma once

#include "integrators/recorder.hpp"
#include "integrators/run_hooks.hpp"
#include "integrators/system.hpp"
#include "lcp/solve.hpp"

#include <span>
#include <string_view>

namespace nsb::integrators {

struct EventDrivenOptions {
  static constexpr std::string_view kMethod = "event_driven";  // solver.method in scene files
  double end_time = 1.0;            // final time [s], > initial time of the system
  double tolerance = 1e-8;          // Odeint absolute and relative error tolerance, in (0, 1)
  lcp::Solver solver = lcp::Solver::kLemke;  // solver of the impact and contact LCPs
  double lcp_tolerance = 1e-12;     // lcp::SolveOptions::tolerance of those solves, > 0
  double event_time_tolerance = 1e-13;  // absolute width [s] of the Brent bracket that
                                        //   locates an event, > 0
  double closing_velocity = 0.0;    // post-impact |gdot_N| [m/s] below which the contact is
                                    //   treated as closed (Zeno); 0 selects 10 * tolerance
  double stick_velocity = 0.0;      // |gdot_T| [m/s] below which a closed contact is a stick
                                    //   candidate; 0 selects 10 * tolerance
  double gap_tolerance = 0.0;       // g_N [m] below which a contact counts as touching at an
                                    //   event, and the drift of a closed contact that is
                                    //   projected away; 0 selects 1e-9 m
  double max_step = 0.0;            // largest smooth-phase step [s]; 0 = limited only by the
                                    //   tolerance and the next event; >= 0
  double initial_step = 1e-4;       // first trial step of a phase [s], > 0
  int max_events_per_window = 2000; // bound on events in any window of length event_window,
                                    //   > 0; reaching it gives a kWarning and forces closure
  double event_window = 1e-2;       // [s], > 0
  // The schema of these fields (keys of a scene's [solver] table, units, ranges).
  static std::span<const config::Field<EventDrivenOptions>> fields();
  void validate() const;            // throws std::invalid_argument naming the key
};

// Integrates `system` from its initial state to options.end_time. Fills the recorder with
// samples at its sample_dt (evaluated on the dense output) and with every event; calls
// progress (may be empty) now and then; shows every contact problem to
// hooks.contact_observer when it is set; returns the run's statistics with method
// "event_driven". Throws std::invalid_argument for bad options or a restart in hooks. Numerical trouble ends the
// run with completed = false, a message and a status: kContactUnsolved (an impact or contact
// problem that no solver of the contact stage's chain solves), kDiverged (a non-finite
// state), kStalled (a step size that underflows, the event bound reached twice in a row).
RunResult event_driven(System& system, const EventDrivenOptions& options, Recorder& recorder,
                       const Progress& progress = {}, const RunHooks& hooks = {});
// The run API's entry for this method (integrators/run.hpp).
inline RunResult run_method(System& system, const EventDrivenOptions& options, Recorder& recorder,
                            const Progress& progress, const RunHooks& hooks) {
  return event_driven(system, options, recorder, progress, hooks);
}

}  // namespace nsb::integrators
