#include "runs/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

namespace nsb::runs {

TracedSystem::TracedSystem(integrators::System& inner, double dt, double duration)
    : inner_(inner) {
  trace_.t0 = inner.initial_time();
  trace_.dt = dt;
  trace_.dofs = inner.dofs();
  if (dt > 0.0 && duration > 0.0 && trace_.dofs > 0) {
    trace_.q.reserve((static_cast<std::size_t>(duration / dt) + 2) *
                     static_cast<std::size_t>(trace_.dofs));
  }
  keep(trace_.t0, inner.initial_position());
}

integrators::StepVerdict TracedSystem::accept_step(const integrators::AcceptedStep& step) {
  if (step.q != nullptr) keep(step.t, *step.q);
  return inner_.accept_step(step);
}

void TracedSystem::keep(double t, const integrators::Vector& q) {
  if (!(trace_.dt > 0.0) || trace_.dofs <= 0) return;
  // A slack for the round-off of a time accumulated step by step.
  const double slack = 1e-9 * trace_.dt;
  for (double g = trace_.t0 + static_cast<double>(trace_.rows()) * trace_.dt; g <= t + slack;
       g = trace_.t0 + static_cast<double>(trace_.rows()) * trace_.dt) {
    const double span = t - last_t_;
    const double w = std::isnan(last_t_) || !(span > 0.0)
                         ? 1.0
                         : std::clamp((g - last_t_) / span, 0.0, 1.0);
    for (int i = 0; i < trace_.dofs; ++i) {
      trace_.q.push_back(w == 1.0 ? q[i] : last_q_[i] + w * (q[i] - last_q_[i]));
    }
  }
  last_t_ = t;
  last_q_ = q;
}

double trace_interval(const integrators::RunConfig& config) {
  const auto* mj = std::get_if<integrators::MoreauJeanOptions>(&config);
  if (mj == nullptr) return kTraceInterval;
  const double coarse = kMoreauStepRatio * mj->step;
  return coarse * std::max(1.0, std::round(kTraceInterval / coarse));
}

double trace_difference(const CoordinateTrace& a, const CoordinateTrace& b, int i, double from,
                        double to) {
  if (a.dofs != b.dofs || a.dt != b.dt || a.t0 != b.t0 || !(a.dt > 0.0) || i < 0 ||
      i >= a.dofs) {
    return 0.0;
  }
  const std::size_t rows = std::min(a.rows(), b.rows());
  const double k0 = std::max(0.0, std::ceil((from - a.t0) / a.dt));
  const double k1 = std::floor((to - a.t0) / a.dt);
  const auto n = static_cast<std::size_t>(a.dofs);
  double d = 0.0;
  for (auto k = static_cast<std::size_t>(k0); k < rows && static_cast<double>(k) <= k1; ++k) {
    const std::size_t at = k * n + static_cast<std::size_t>(i);
    d = std::max(d, std::abs(std::abs(a.q[at]) - std::abs(b.q[at])));
  }
  return d;
}

namespace {

// The peak of a history column by name; nullptr when there is none.
const ColumnPeak* column_peak(const Digest& d, const std::string& name) {
  for (const ColumnPeak& p : d.peaks) {
    if (p.column == name) return &p;
  }
  return nullptr;
}

// The largest |u_i| over a run's steps (the velocity column of coordinate i); 0 without one.
double velocity_magnitude(const integrators::Recorder& history, int i) {
  const std::vector<integrators::Column>& info = history.column_info();
  for (std::size_t c = 1; c < info.size(); ++c) {
    if (info[c].kind == integrators::ColumnKind::kVelocity && info[c].index == i) {
      return history.extremes()[c - 1].magnitude;
    }
  }
  return 0.0;
}

}  // namespace

void bound_by_trajectories(Digest& run, const integrators::Recorder& run_history,
                           const CoordinateTrace& run_trace, const Digest& companion,
                           const CoordinateTrace& companion_trace, const CompanionPlan& plan) {
  // The floor's argument is an impact's instant: none without an impact in either run.
  const bool impacts = run.count(integrators::EventKind::kImpact) > 0 ||
                       companion.count(integrators::EventKind::kImpact) > 0;
  for (std::size_t c = 0; c < run.coordinates.size() && c < companion.coordinates.size(); ++c) {
    CoordinatePeak& mine = run.coordinates[c];
    const ColumnPeak* pa = column_peak(run, mine.name);
    const ColumnPeak* pb = column_peak(companion, mine.name);
    double bound = 0.0;
    if (pa != nullptr && pb != nullptr && std::isfinite(pa->t_abs_max) &&
        std::isfinite(pb->t_abs_max)) {
      bound = trace_difference(run_trace, companion_trace, static_cast<int>(c),
                               std::min(pa->t_abs_max, pb->t_abs_max) - kPeakWindow,
                               std::max(pa->t_abs_max, pb->t_abs_max) + kPeakWindow);
    }
    double error = std::max(mine.error, plan.factor * bound);
    if (plan.setting == "step" && impacts) {
      error = std::max(error, kImpactShiftBound * plan.value *
                                  velocity_magnitude(run_history, static_cast<int>(c)));
    }
    mine.error = error;
    for (ColumnPeak& p : run.peaks) {
      if (p.column == mine.name) p.error = std::max(p.error, error);
    }
  }
}

}  // namespace nsb::runs
