#include "integrators/run_bookkeeping.hpp"

#include <stdexcept>
#include <string>

namespace nsb::integrators {

namespace {

// Number of lcp::Status values (kNotRun .. kTooLarge).
constexpr int kStatusCount = static_cast<int>(lcp::Status::kTooLarge) + 1;

}  // namespace

RunBookkeeping::RunBookkeeping(std::string_view method, const Progress& progress,
                               std::int64_t progress_interval)
    : progress_(progress),
      interval_mask_(progress_interval - 1),
      start_(std::chrono::steady_clock::now()) {
  if (progress_interval < 1 || (progress_interval & interval_mask_) != 0) {
    throw std::invalid_argument("RunBookkeeping: progress_interval must be a power of two, got " +
                                std::to_string(progress_interval));
  }
  result_.method = std::string(method);
}

RunResult RunBookkeeping::finish(double end_time, bool completed, const EnergyBalance& energy,
                                 const ContactStageCounts* counts) {
  if (progress_) progress_(end_time);
  result_.completed = completed;
  result_.end_time = end_time;
  result_.energy = energy;
  if (!std::isfinite(energy.error)) diverge(end_time);
  if (counts != nullptr) {
    result_.lcp_solves = counts->solves;
    result_.lcp_fallbacks = counts->fallbacks;
    result_.lcp_unsolved = counts->unsolved;
    for (int s = 0; s < kStatusCount; ++s) {
      if (counts->by_status[s] > 0) {
        result_.lcp_status[std::string(lcp::to_string(static_cast<lcp::Status>(s)))] =
            counts->by_status[s];
      }
    }
  }
  // A run that stopped short without diverging and without an unsolved contact problem could
  // not advance (a step size underflow, max_steps): stalled.
  const bool stopped_short =
      !completed && !diverged_ && !unseated_ && !interrupted_ && result_.lcp_unsolved == 0;
  finish_status(result_, diverged_, stalled_ || stopped_short, unseated_, interrupted_);
  if (result_.status == RunStatus::kInterrupted) result_.message = "interrupted";
  if (!succeeded(result_.status)) {
    const double failure = result_.status == RunStatus::kContactUnsolved ? first_unsolved_
                                                                          : stop_time_;
    result_.failure_time = std::isnan(failure) ? end_time : failure;
  }
  result_.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return result_;
}

}  // namespace nsb::integrators
