// The work one run may take, the same rule for every method (docs/scenes.md, "The work of a
// run"): at most kMaxSteps accepted steps and kMaxRows rows of history.
//
//   - Before the run, work_misfit() counts the fewest steps the options allow over
//     [t0, end_time] (the duration over the largest step: Moreau–Jean's step, the compliance
//     method's max_step, the event-driven max_step when it is given) and the rows the
//     history will hold (the duration over output.sample_dt, or one per step when it is 0),
//     and names the key that makes either too large: bad input, refused before any work.
//   - During an adaptive run (event-driven, compliance), whose steps are not known before,
//     PaceWatch looks every kPaceBlock accepted steps at the time the block advanced: when
//     the rest of the run at that pace would take the run past kMaxSteps steps, the step
//     size has collapsed (a stiffness of 1e15 kN/m, a chattering contact) and the run stops
//     there, stalled, with the time and the pace in its message.
//
// Why these values: the longest shipped run takes 3.4e6 steps (bridge-backfill, compliance,
// 40 s) and writes 8003 rows; kMaxSteps = 1e8 is 29 times that, a few minutes of wall time
// at the methods' microseconds per step. A row of the bridge's history is about 60 numbers
// (500 B in memory and on disk), so kMaxRows = 1e7 rows is 5 GB: a history beyond it is a
// unit mistake (a sample_dt in ms typed in s) rather than a plan.
#pragma once

#include "integrators/run.hpp"

#include <cstdint>
#include <string>

namespace nsb::integrators {

inline constexpr double kMaxSteps = 1e8;  // accepted steps of one run
inline constexpr double kMaxRows = 1e7;   // rows of one run's history
// Accepted steps between two looks of PaceWatch (a power of two: the test is a mask).
inline constexpr std::int64_t kPaceBlock = 8192;
// An end_time beyond this [s] (11.6 days, longer than any ground-motion record) is named as
// the cause of too much work rather than the step that divides it.
inline constexpr double kLongRun = 1e6;

// Why the run of config over [t0, end_time] with its history sampled every sample_dt [s]
// (0: every step) would take more than kMaxSteps steps or kMaxRows rows, as
// "<key>: <what>" with key one of end_time, step, max_step (of [solver]) or sample_dt (of
// [output]); "" when it would not. step_given / sample_given: whether the scene sets the
// step key of its method (step, max_step) and output.sample_dt: a key left at its default is
// not named as the cause while end_time is given.
std::string work_misfit(const RunConfig& config, double t0, double sample_dt,
                        bool step_given = true, bool sample_given = true);

// The pace check of an adaptive run (above).
class PaceWatch {
 public:
  PaceWatch(double t0, double end_time) : block_start_(t0), end_time_(end_time) {}
  // Called after every accepted step with the count of accepted steps and the time reached;
  // returns the reason to stop ("" to go on), looking only every kPaceBlock steps.
  std::string collapsed(std::int64_t steps, double t) {
    if ((steps & (kPaceBlock - 1)) != 0) return {};
    return look(steps, t);
  }

 private:
  std::string look(std::int64_t steps, double t);
  double block_start_;
  double end_time_;
};

}  // namespace nsb::integrators
