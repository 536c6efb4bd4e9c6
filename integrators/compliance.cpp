#include "integrators/compliance.hpp"

#include "integrators/compliance_integrator.hpp"
#include "integrators/work_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nsb::integrators::compliance_detail {

namespace {

bool finite(const State& x) { return x.allFinite(); }

}  // namespace

RunResult ComplianceRun::integrate() {
  RunResult& stats = book_.result();
  start();
  double dt = std::min(options_.initial_step, options_.max_step);
  const double time_scale = std::max(1.0, std::abs(options_.end_time));
  PaceWatch pace(t_, options_.end_time);
  while (t_ < options_.end_time) {
    if (stats.steps + stats.rejected_steps >= options_.max_steps) {
      stats.message = "max_steps reached";
      break;
    }
    dt = std::min({dt, options_.end_time - t_, target_ - t_});
    if (dt < kMinRelativeStep * std::max(1.0, std::abs(t_))) {
      std::ostringstream os;
      os << "step size underflow at t = " << t_;
      stats.message = os.str();
      break;
    }
    const double dt_try = dt;
    double t_new = t_;
    ++stats.factorizations;
    const bool ok = stepper_.try_step(x_, t_new, xnew_, dt);
    if (!ok || !finite(xnew_)) {
      if (ok) dt = 0.5 * dt_try;  // a finite error estimate but a non-finite state: halve
      ++stats.rejected_steps;
      continue;
    }
    // Landing exactly on the end time or the closure target must not be missed by
    // round-off.
    if (std::abs(t_new - options_.end_time) <= 1e-14 * time_scale) t_new = options_.end_time;
    const bool landed = std::abs(t_new - target_) <= 1e-14 * time_scale;
    if (landed) t_new = target_;

    const Closure closure = locate_closure(t_new, landed);
    if (closure.retake) {
      // Retake the step so that it ends at the closure: contact onset is a step boundary.
      target_ = closure.time;
      dt = closure.time - t_;
      ++stats.rejected_steps;
      continue;
    }
    if (!accept_step(t_new, landed, closure.at_start)) break;
    if (std::string why = pace.collapsed(stats.steps, t_); !why.empty()) {
      stats.message = std::move(why);
      book_.stall(t_);
      break;
    }
    book_.progress_at_interval(t_);
    if (book_.interrupted()) break;
  }
  const bool completed = t_ >= options_.end_time;
  recorder_.sample_now(t_, core_.q_, core_.u_, core_.contacts_, core_.lambda_n_,
                       core_.lambda_t_, energy_.error);
  if (!completed && stats.message.empty()) stats.message = "stopped before end_time";
  // A non-finite state is never accepted (the step is halved), so a run that cannot advance
  // past one ends in a step underflow: stalled, like max_steps. A non-finite energy balance
  // is divergence.
  return book_.finish(t_, completed, energy_, nullptr);
}

void ComplianceRun::start() {
  t_ = system_.initial_time();
  x_ = State::Zero(2 * n_);
  xnew_ = State::Zero(2 * n_);
  momentum_ = Vector::Zero(n_);
  const Vector q0 = system_.initial_position();
  const Vector u0 = system_.initial_velocity();
  if (q0.size() != n_ || u0.size() != n_) {
    throw std::invalid_argument("compliance: initial state size differs from dofs()");
  }
  x_.head(n_) = q0;
  x_.tail(n_) = u0;
  core_.evaluate(t_, x_, false, ContactFields::kAll);
  for (int i = 0; i < m_; ++i) {
    const ContactData& c = core_.contacts_[static_cast<std::size_t>(i)];
    core_.chi_[i] = damping_factor(options_.law, c.restitution);
  }
  for (int i = 0; i < m_; ++i) {
    const ContactData& c = core_.contacts_[static_cast<std::size_t>(i)];
    if (!c.far && c.gap_normal <= 0.0) close_contact(i, t_);
  }
  core_.evaluate(t_, x_, false, ContactFields::kAll);
  system_.commit();
  update_state_energy();
  energy_.initial = energy_.kinetic + energy_.stored;
  energy_.close();
  p_old_ = powers();
  impulse_ = Vector::Zero(m_);
  lambda_start_ = core_.lambda_n_;
  accepted_.q = &core_.q_;
  accepted_.u = &core_.u_;
  accepted_.normal_impulse = &impulse_;
  recorder_.step(t_, core_.q_, core_.u_, core_.contacts_, core_.lambda_n_, core_.lambda_t_,
                 0.0);
  start_gap_ = Vector::Zero(m_);
  start_rate_ = Vector::Zero(m_);
  remember_start();
}

}  // namespace nsb::integrators::compliance_detail

namespace nsb::integrators {

RunResult compliance(System& system, const ComplianceOptions& options, Recorder& recorder,
                     const Progress& progress, const std::atomic<bool>* stop) {
  options.validate();
  if (!(options.end_time > system.initial_time())) {
    throw std::invalid_argument("compliance options: end_time: must be > the initial time");
  }
  compliance_detail::ComplianceRun run(system, options, recorder, progress);
  run.watch(stop);
  return run.integrate();
}

}  // namespace nsb::integrators
