#include "integrators/event_driven.hpp"

#include "integrators/event_integrator.hpp"
#include "integrators/work_bounds.hpp"
#include "io/csv.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace nsb::integrators {

namespace detail {

namespace {

// Default gap_tolerance [m]: closed contacts are projected back once they drift further, and
// open contacts count as touching at an event within it. An absolute length, not a multiple
// of the (relative) tolerance: at tolerance 1e-3 that would be 1 cm, the size of the gaps.
constexpr double kDefaultGapTolerance = 1e-9;
// Accepted steps between two calls of the progress callback.
constexpr std::int64_t kProgressInterval = 1024;
// A step shorter than this times max(1 s, |t|) means the step size has underflowed.
constexpr double kMinStep = 1e-14;

bool all_finite(const State& x) {
  return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

EventDriven::EventDriven(System& system, const EventDrivenOptions& options, Recorder& recorder,
                         const Progress& progress, const RunHooks& hooks)
    : sys_(system),
      opt_(options),
      rec_(recorder),
      book_(EventDrivenOptions::kMethod, progress, kProgressInterval),
      roots_(options.event_time_tolerance) {
  book_.watch(hooks.stop);
  // Every recorded state passes through indicators() (f_ there) and balance_error() (energy_).
  rec_.watch(&energy_, &f_);
  n_ = sys_.dofs();
  m_ = sys_.contacts();
  const double tol = opt_.tolerance;
  closing_velocity_ = opt_.closing_velocity > 0.0 ? opt_.closing_velocity : 10.0 * tol;
  stick_velocity_ = opt_.stick_velocity > 0.0 ? opt_.stick_velocity : 10.0 * tol;
  gap_tolerance_ = opt_.gap_tolerance > 0.0 ? opt_.gap_tolerance : kDefaultGapTolerance;
  gap_shift_ = 1e-2 * gap_tolerance_;
  minv_ = checked_inverse_mass(sys_, "event_driven");
  cbuf_ = sys_.make_contact_buffer();
  modes_.assign(static_cast<std::size_t>(m_), ContactState::kOpen);
  f_ = Vector::Zero(n_);
  q_ = Vector::Zero(n_);
  u_ = Vector::Zero(n_);
  udot_ = Vector::Zero(n_);
  lambda_n_ = Vector::Zero(m_);
  lambda_t_ = Vector::Zero(m_);
  h_ = Vector::Zero(2 * m_);
  h_prev_ = Vector::Zero(2 * m_);
  h_end_ = Vector::Zero(2 * m_);
  phase_b_ = Matrix::Zero(n_, 2 * m_);
  phase_r_ = Matrix::Zero(n_, 2 * m_);
  phase_rt_minv_ = Matrix::Zero(2 * m_, n_);
  phase_wbar_ = Vector::Zero(2 * m_);
  phase_a_free_ = Vector::Zero(n_);
  phase_lambda_ = Vector::Zero(2 * m_);
  phase_b_lambda_ = Vector::Zero(n_);
  xs_.assign(static_cast<std::size_t>(2 * n_ + kEnergyTerms), 0.0);
  ContactStageOptions stage_options;
  stage_options.solver = opt_.solver;
  stage_options.tolerance = opt_.lcp_tolerance;
  stage_options.observer = hooks.contact_observer;
  stage_ = ContactStage(n_, m_, stage_options);
  touching_.reserve(static_cast<std::size_t>(m_));
  candidates_.reserve(static_cast<std::size_t>(m_));
  slip_coupling_.assign(static_cast<std::size_t>(m_), 0.0);
  u_plus_ = Vector::Zero(n_);
  q_event_ = Vector::Zero(n_);
  u_event_ = Vector::Zero(n_);
  a_free_ = Vector::Zero(n_);
  step_impulse_ = Vector::Zero(m_);
  impact_impulse_ = Vector::Zero(m_);
  lambda_start_ = Vector::Zero(m_);
  accepted_.q = &q_;
  accepted_.u = &u_;
  accepted_.normal_impulse = &step_impulse_;
  accepted_.impact_impulse = &impact_impulse_;
}

RunResult EventDriven::run() {
  if (!start()) return finish(false);
  const double t_end = opt_.end_time;
  PaceWatch pace(t_, t_end);
  while (t_ < t_end) {
    const StepEnd end = step();
    if (end == StepEnd::kStop || book_.interrupted()) return finish(false);
    if (end == StepEnd::kEndTime) break;
    if (std::string why = pace.collapsed(book_.result().steps, t_); !why.empty()) {
      warn(t_, 0, why);
      book_.result().message = std::move(why);
      book_.stall(t_);
      return finish(false);
    }
  }
  t_ = std::min(t_, t_end);
  return finish(true);
}

// The initial state (checked), its energy, the event at t0 (contacts touching or penetrating
// at the start decide the first phase's modes), the first sample and the first phase.
// Returns false when that event stops the run.
bool EventDriven::start() {
  t_ = sys_.initial_time();
  if (!(opt_.end_time > t_)) {
    throw std::invalid_argument("event_driven options: end_time must be > the initial time " +
                                io::three_digits(t_) + " s");
  }
  x_.assign(static_cast<std::size_t>(2 * n_ + kEnergyTerms), 0.0);
  {
    const Vector q0 = sys_.initial_position(), u0 = sys_.initial_velocity();
    if (q0.size() != n_ || u0.size() != n_) {
      throw std::invalid_argument("event_driven: initial state has the wrong size");
    }
    pack(q0, u0, x_);
    initial_energy_ = 0.5 * u0.dot(sys_.mass() * u0) + sys_.energy(t_, q0).stored;
  }
  dense_ = odeint::make_dense_output(opt_.tolerance, opt_.tolerance, opt_.max_step, Dopri());
  if (!handle_event(t_, x_, 0, true)) return false;
  sys_.commit();
  record_sample(t_, x_, SampleKind::kStep);
  const double sample_dt = rec_.sample_dt();
  next_sample_ = sample_dt > 0.0 ? t_ + sample_dt : t_;
  restart_phase(std::min(opt_.initial_step, opt_.end_time - t_));
  return true;
}

// A smooth phase starts at (t_, x_) with a first trial step dt: the stepper restarts there and
// the indicators at the start are those of the phase's modes.
void EventDriven::restart_phase(double dt) {
  dense_.initialize(x_, t_, dt);
  indicators(t_, x_);
  h_prev_ = h_;
  lambda_start_ = lambda_n_;
}

// One step of the dense-output stepper, cut at the earliest event in it: samples up to there,
// then the event's resolution or the end of a smooth step.
EventDriven::StepEnd EventDriven::step() {
  double ta = 0.0, tb = 0.0;
  if (!attempt_step(ta, tb)) return StepEnd::kStop;
  book_.progress_at_interval(tb);
  indicators(tb, x_);
  h_end_ = h_;
  double t_event = std::numeric_limits<double>::infinity();
  const int k_event = earliest_event(ta, tb, t_event);
  const double t_stop = std::min(t_event, tb);
  sample_until(t_stop);
  t_ = t_stop;
  dense_.calc_state(t_, x_);
  phase_impulse(ta, t_stop);
  record_step();
  if (k_event >= 0 && t_event <= tb) return after_event(k_event);
  return after_smooth_step();
}

// Advances the stepper by one controlled step [ta, tb] (tb no later than end_time) and puts
// the state at tb into x_. False when the step size underflows (stalled) or the state went
// non-finite (diverged); the run then ends at ta with the state there.
bool EventDriven::attempt_step(double& ta, double& tb) {
  auto rhs_fn = [this](const State& xx, State& dxdt, double tt) { rhs(xx, dxdt, tt); };
  const std::int64_t evals0 = rhs_evaluations_;
  dense_.do_step(std::ref(rhs_fn));
  const std::int64_t evals = rhs_evaluations_ - evals0;
  RunResult& r = book_.result();
  // Dormand–Prince with FSAL costs six right-hand sides per attempt, plus one for the
  // derivative at the start of a phase (after initialize()).
  r.rejected_steps += std::max<std::int64_t>(0, evals / 6 - 1);
  book_.count_step();
  ta = dense_.previous_time();
  tb = std::min(dense_.current_time(), opt_.end_time);
  if (!(dense_.current_time_step() > kMinStep * std::max(1.0, std::abs(ta)))) {
    r.message = "step size underflow at t = " + io::three_digits(ta) + " s";
    warn(ta, 0, r.message);
    book_.stall(ta);
  } else {
    dense_.calc_state(tb, x_);
    if (all_finite(x_)) return true;
    // The step went non-finite (a force blew up): stop at its start, the last finite state.
    book_.diverge(ta);
    r.message = "non-finite state in the step from t = " + io::three_digits(ta) + " s";
    warn(ta, 0, r.message);
  }
  t_ = ta;
  dense_.calc_state(ta, x_);
  return false;
}

// Earliest event in (ta, tb]: its indicator (2 i for contact i's normal event, 2 i + 1 for its
// tangential one), -1 for none; t_event is its time, +inf for none.
int EventDriven::earliest_event(double ta, double tb, double& t_event) {
  int k_event = -1;
  for (int k = 0; k < 2 * m_; ++k) {
    const double te = locate(k, ta, tb, h_prev_[k], h_end_[k]);
    if (te < t_event) {
      t_event = te;
      k_event = k;
    }
  }
  return k_event;
}

// Samples from the dense output of the current step at the sampling times up to t_stop.
void EventDriven::sample_until(double t_stop) {
  const double sample_dt = rec_.sample_dt();
  if (!(sample_dt > 0.0)) return;
  while (next_sample_ <= t_stop) {
    dense_.calc_state(next_sample_, xs_);
    record_sample(next_sample_, xs_, SampleKind::kBetweenSteps);
    next_sample_ += sample_dt;
  }
}

// Resolves the event of indicator k_event at t_, commits, and starts the next phase.
EventDriven::StepEnd EventDriven::after_event(int k_event) {
  if (!handle_event(t_, x_, k_event / 2 + 1, false)) {
    sys_.commit();
    return StepEnd::kStop;
  }
  sys_.commit();
  if (accept_step() == StepVerdict::kUnseated) return StepEnd::kStop;
  const double t_end = opt_.end_time;
  double dt = std::max(dense_.current_time_step(), 1e3 * kMinStep * std::max(1.0, std::abs(t_)));
  dt = std::min(dt, std::max(t_end - t_, kMinStep));
  if (t_ >= t_end) return StepEnd::kEndTime;
  restart_phase(dt);
  return StepEnd::kGoOn;
}

// No event in the step: commits its end state, and projects the closed contacts back onto
// their constraints when they drifted beyond gap_tolerance or closing_velocity.
EventDriven::StepEnd EventDriven::after_smooth_step() {
  unpack(x_, q_, u_);
  sys_.forces(t_, q_, u_, f_);
  sys_.commit();
  const StepVerdict verdict = accept_step();
  if (verdict == StepVerdict::kUnseated) return StepEnd::kStop;
  h_prev_ = h_end_;
  if (t_ >= opt_.end_time) return StepEnd::kEndTime;
  if (verdict == StepVerdict::kContactsRemoved) {
    restart_phase(dense_.current_time_step());
    return StepEnd::kGoOn;
  }
  bool drift = false;
  sys_.contact_data(t_, q_, u_, cbuf_);
  for (int i = 0; i < m_; ++i) {
    if (!closed(modes_[idx(i)])) continue;
    const auto& c = cbuf_[idx(i)];
    drift = drift || std::abs(c.gap_normal) > gap_tolerance_ ||
            std::abs(c.gap_rate(u_)) > closing_velocity_;
  }
  if (drift) {
    Vector q = q_, u = u_;
    project_positions(t_, q, u);
    project_velocities(t_, q, u);
    pack(q, u, x_);
    restart_phase(dense_.current_time_step());
  }
  return StepEnd::kGoOn;
}

// The closed phase's contact forces over the step [ta, tb] by the trapezoidal rule, in the
// phase's modes: lambda_N at tb (indicators() there, as a sample at tb would) with
// lambda_start_ at ta. Nothing when no contact is closed (the phase's lambda_N are zero).
void EventDriven::phase_impulse(double ta, double tb) {
  bool any_closed = false;
  for (const auto& md : modes_) any_closed = any_closed || closed(md);
  if (!any_closed) return;
  indicators(tb, x_);
  const double half = 0.5 * (tb - ta);
  for (int i = 0; i < m_; ++i) step_impulse_[i] += half * (lambda_start_[i] + lambda_n_[i]);
  lambda_start_ = lambda_n_;
}

// Hands the accepted step ending at t_ (state x_) to the system with its normal impulses,
// then clears them. On kContactsRemoved the removed contacts (far from now on) leave the
// phase's modes; the caller restarts the phase. On kUnseated the run stops here.
StepVerdict EventDriven::accept_step() {
  unpack(x_, q_, u_);
  accepted_.t = t_;
  accepted_.h = t_ - t_start_;
  const StepVerdict verdict = sys_.accept_step(accepted_);
  step_impulse_.setZero();
  impact_impulse_.setZero();
  t_start_ = t_;
  if (verdict == StepVerdict::kContactsRemoved) {
    record_removed_contacts(sys_, t_, rec_);
    drop_removed_contacts();
  }
  if (verdict == StepVerdict::kUnseated) {
    book_.unseat(t_);
    book_.result().message = "unseated at t = " + io::three_digits(t_) + " s";
  }
  return verdict;
}

// A contact the system removed is far: a closed one opens (an "open" event) and is never
// part of a phase again, as an open far contact has no indicator that could close it.
void EventDriven::drop_removed_contacts() {
  sys_.contact_normals(t_, q_, u_, cbuf_);
  for (int i = 0; i < m_; ++i) {
    if (!cbuf_[idx(i)].far || modes_[idx(i)] == ContactState::kOpen) continue;
    modes_[idx(i)] = ContactState::kOpen;
    rec_.event(t_, i + 1, EventKind::kOpen);
  }
}

// The last sample, and the run's result. A non-finite state is not recorded (nor handed to
// the system): the history ends with the last finite sample, and the run diverged.
RunResult EventDriven::finish(bool completed) {
  if (all_finite(x_)) {
    record_sample(t_, x_, SampleKind::kForced);
  } else {
    book_.diverge(t_);
  }
  return book_.finish(t_, completed, energy_, &stage_.counts());
}

double EventDriven::balance_error(double t, const State& x) {
  Vector q(n_), u(n_);
  unpack(x, q, u);
  EnergyBalance e;
  const EnergyState es = sys_.energy(t, q);
  e.kinetic = 0.5 * u.dot(sys_.mass() * u);
  e.stored = es.stored;
  e.hysteretic = es.hysteretic;
  e.initial = initial_energy_;
  e.damping = energy_term(x, kDamping);
  e.ground = energy_term(x, kGround) + impact_ground_work_;
  e.external = energy_term(x, kExternal);
  e.impacts = energy_term(x, kNormal) + impact_normal_work_;
  e.friction = energy_term(x, kFriction) + impact_friction_work_;
  e.close();
  energy_ = e;
  return e.error;
}

void EventDriven::record_sample(double t, const State& x, SampleKind kind) {
  indicators(t, x);  // fills contact data and the phase's contact forces at (t, x)
  const double err = balance_error(t, x);
  switch (kind) {
    case SampleKind::kBetweenSteps: rec_.sample(t, q_, u_, cbuf_, lambda_n_, lambda_t_, err); break;
    case SampleKind::kStep: rec_.step(t, q_, u_, cbuf_, lambda_n_, lambda_t_, err); break;
    case SampleKind::kForced: rec_.sample_now(t, q_, u_, cbuf_, lambda_n_, lambda_t_, err); break;
  }
}

void EventDriven::record_step() {
  if (rec_.sample_dt() == 0.0) {
    record_sample(t_, x_, SampleKind::kStep);
    return;
  }
  indicators(t_, x_);
  rec_.observe(t_, q_, u_, cbuf_, lambda_n_, lambda_t_, balance_error(t_, x_));
}

}  // namespace detail

RunResult event_driven(System& system, const EventDrivenOptions& options, Recorder& recorder,
                       const Progress& progress, const RunHooks& hooks) {
  options.validate();
  require_no_restart(hooks, EventDrivenOptions::kMethod);
  detail::EventDriven integrator(system, options, recorder, progress, hooks);
  return integrator.run();
}

}  // namespace nsb::integrators
