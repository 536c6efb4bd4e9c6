// What every integrator records about its run besides the motion: the counters of
// RunResult, the progress callback at intervals, the wall clock, what stopped the run
// (divergence, stall, a contact problem no solver solved) with its time, and, at the end,
// the closed energy balance, the contact stage's counts and the status (finish_status).
//
// Moreau–Jean, event-driven and compliance keep one each. The per-step calls are inline and
// allocate nothing; only a failure (its message) and finish() allocate.
#pragma once

#include "integrators/contact_stage.hpp"
#include "integrators/recorder.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>

namespace nsb::integrators {

class RunBookkeeping {
 public:
  // Starts the wall clock. progress (may be empty) is called every progress_interval
  // accepted steps and once at the end; it must outlive this object. progress_interval is a
  // power of two (the test per step is then a mask, not a division); throws
  // std::invalid_argument otherwise.
  RunBookkeeping(std::string_view method, const Progress& progress,
                 std::int64_t progress_interval);

  // The result being filled: integrators add their own counters (factorizations,
  // steps_with_lcp, rejected_steps), the message and warnings here.
  RunResult& result() { return result_; }

  // One accepted step.
  void count_step() { ++result_.steps; }
  // Reads stop (RunHooks::stop; may be nullptr) at every accepted step.
  void watch(const std::atomic<bool>* stop) { stop_ = stop; }
  // Reads the stop request, which ends the run at t (interrupted()), at every step: a relaxed
  // load costs nanoseconds against a step's microseconds, and a step slowed by what observes
  // it (--dump-lcp writes every contact problem) still stops within one step. When the
  // accepted steps are a multiple of the interval, calls progress with the time reached and
  // reads the request again (a Python caller sets it from the callback).
  void progress_at_interval(double t) {
    if (stop_ != nullptr && stop_->load(std::memory_order_relaxed)) interrupt(t);
    if ((result_.steps & interval_mask_) != 0) return;
    if (progress_) progress_(t);
    if (stop_ != nullptr && stop_->load(std::memory_order_relaxed)) interrupt(t);
  }
  // A stop was requested at t (RunStatus::kInterrupted): the integrator ends the run.
  void interrupt(double t) {
    interrupted_ = true;
    if (std::isnan(stop_time_)) stop_time_ = t;
  }
  bool interrupted() const { return interrupted_; }

  // A non-finite state, force or energy stopped the run at time t (RunStatus::kDiverged).
  void diverge(double t) {
    diverged_ = true;
    if (std::isnan(stop_time_)) stop_time_ = t;
  }
  bool diverged() const { return diverged_; }
  // The method could not advance past t (RunStatus::kStalled).
  void stall(double t) {
    stalled_ = true;
    if (std::isnan(stop_time_)) stop_time_ = t;
  }
  // The system stopped the run at t (StepVerdict::kUnseated; RunStatus::kUnseated).
  void unseat(double t) {
    unseated_ = true;
    if (std::isnan(stop_time_)) stop_time_ = t;
  }
  bool unseated() const { return unseated_; }
  // A contact problem no solver of the chain solved at t (RunStatus::kContactUnsolved from
  // then on; the run may go on).
  void note_unsolved(double t) {
    if (std::isnan(first_unsolved_)) first_unsolved_ = t;
  }

  // Ends the run at end_time [s]: completed says whether end_time of the options was reached.
  // Copies the energy balance (divergence when its error is not finite) and the contact
  // stage's counts (nullptr: no contact problems), sets the status by finish_status (a run
  // that stopped short without diverging, unseating, an interruption or an unsolved contact
  // problem has stalled),
  // failure_time (the first unsolved problem for kContactUnsolved, else where the run
  // stopped) and the wall time, and calls progress once more.
  RunResult finish(double end_time, bool completed, const EnergyBalance& energy,
                   const ContactStageCounts* counts);

 private:
  RunResult result_;
  const Progress& progress_;
  std::int64_t interval_mask_ = 0;  // progress_interval - 1
  std::chrono::steady_clock::time_point start_;
  bool diverged_ = false;
  bool stalled_ = false;
  bool unseated_ = false;
  bool interrupted_ = false;
  const std::atomic<bool>* stop_ = nullptr;
  double stop_time_ = std::numeric_limits<double>::quiet_NaN();       // [s]
  double first_unsolved_ = std::numeric_limits<double>::quiet_NaN();  // [s]
};

}  // namespace nsb::integrators
