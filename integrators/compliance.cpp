#include "integrators/compliance.hpp"

#include "integrators/closure_bound.hpp"
#include "integrators/rosenbrock.hpp"
#include "integrators/run_bookkeeping.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace nsb::integrators {

namespace {

using State = Eigen::VectorXd;
using JacobianMatrix = Eigen::MatrixXd;

// Interior points of an accepted step at which the interpolated gaps are inspected for a
// closure. A gap that dips below zero and comes back within 1/8 of a free-flight step is
// caught by the Hermite cubic only if it is negative at one of these points; 8 points keep
// the check cheap (one contact_data call each) while a free flight that passes through an
// obstacle is a parabola-like arc that cannot hide between them.
constexpr int kClosureProbes = 8;
// Bisection of the closure time stops when the bracket is this fraction of the step: the
// located time then sits within round-off of the interpolant's root.
constexpr double kClosureRelativeWidth = 1e-12;
constexpr int kMaxBisections = 60;
// Relative step of the forward difference for df/dt (the rheonomic and load terms):
// sqrt(machine epsilon), the usual optimum for a one-sided difference.
const double kTimeDifferenceStep = std::sqrt(std::numeric_limits<double>::epsilon());
// A step shorter than this fraction of max(1 s, |t|) means the step size has underflowed.
constexpr double kMinRelativeStep = 1e-14;
// Accepted steps between two calls of the progress callback.
constexpr std::int64_t kProgressInterval = 4096;

// Hermite basis on [0, 1] for position from (q0, u0 h, q1, u1 h): exact for cubics.
struct Hermite {
  double h00, h10, h01, h11;
  explicit Hermite(double s)
      : h00(2 * s * s * s - 3 * s * s + 1), h10(s * s * s - 2 * s * s + s),
        h01(-2 * s * s * s + 3 * s * s), h11(s * s * s - s * s) {}
};

// Which contact fields an evaluation leaves current: kForces those the contact forces read
// (all of them for penetrated contacts, the normal part otherwise), kAll every field of every
// contact (accepted states: the events and the energy balance read the tangential ones).
enum class ContactFields { kForces, kAll };

// The state of the integration: the system, its constant mass matrix, and every buffer the
// right-hand side and the Jacobian need, sized once.
class Core {
 public:
  Core(System& system, const ComplianceOptions& o)
      : sys_(system), opt_(o), n_(system.dofs()), m_(system.contacts()) {
    minv_ = checked_inverse_mass(sys_, "compliance");
    q_ = Vector::Zero(n_);
    u_ = Vector::Zero(n_);
    f_ = Vector::Zero(n_);
    acc_ = Vector::Zero(n_);
    K_ = Matrix::Zero(n_, n_);
    C_ = Matrix::Zero(n_, n_);
    Jq_ = Matrix::Zero(n_, n_);
    Ju_ = Matrix::Zero(n_, n_);
    contacts_ = sys_.make_contact_buffer();
    probes_ = sys_.make_contact_buffer();
    lambda_n_ = Vector::Zero(m_);
    lambda_t_ = Vector::Zero(m_);
    damping_part_ = Vector::Zero(m_);
    chi_ = Vector::Zero(m_);
    v_minus_ = Vector::Constant(m_, opt_.min_impact_velocity);
  }

  int dofs() const { return n_; }
  int contacts() const { return m_; }

  // Loads q, u from x and evaluates f, the contact data and the contact forces at (t, q, u).
  // With derivatives, also fills Jq_ = -dF/dq and Ju_ = -dF/du of the generalized contact
  // force F = sum W_N lambda_N + W_T lambda_T (geometric terms dW/dq neglected: see below).
  // `data` says which contact fields must be current afterwards (ContactFields).
  void evaluate(double t, const State& x, bool derivatives,
                ContactFields data = ContactFields::kForces) {
    q_ = x.head(n_);
    u_ = x.tail(n_);
    sys_.forces(t, q_, u_, f_);
    load_contacts(t, data);
    if (derivatives) {
      Jq_.setZero();
      Ju_.setZero();
    }
    for (int i = 0; i < m_; ++i) {
      lambda_n_[i] = 0.0;
      lambda_t_[i] = 0.0;
      damping_part_[i] = 0.0;
      const ContactData& c = contacts_[static_cast<std::size_t>(i)];
      if (c.far || !(c.gap_normal < 0.0)) continue;
      const NormalForce fn = normal_force(i, c);
      const TangentForce ft = tangent_force(i, c, fn);
      if (derivatives) add_contact_jacobian(c, fn, ft);
    }
  }

  // Gaps, W and the rheonomic terms (eq. 2) at (t, q_, u_). For the forces alone the normal
  // part comes first (System::contact_normals, the same numbers for a fraction of the work):
  // eqs. (9) and (10) act only on penetrated contacts, so the full data are needed only when
  // one is; while every gap is open the tangential fields keep stale values nobody reads.
  void load_contacts(double t, ContactFields data) {
    if (data == ContactFields::kForces) {
      sys_.contact_normals(t, q_, u_, contacts_);
      const bool penetrated = std::any_of(contacts_.begin(), contacts_.end(),
                                          [](const ContactData& c) {
                                            return !c.far && c.gap_normal < 0.0;
                                          });
      if (!penetrated) return;
    }
    sys_.contact_data(t, q_, u_, contacts_);
  }

  // Eq. (9) on the penetration delta = -g_N and its rate -gdot_N, added to f along W_N.
  NormalForce normal_force(int i, const ContactData& c) {
    const double delta = -c.gap_normal;
    const double delta_rate = -c.gap_rate(u_);
    const NormalForce fn =
        hertz_damp_force(opt_.effective_stiffness(), chi_[i], v_minus_[i], delta, delta_rate);
    lambda_n_[i] = fn.force;
    damping_part_[i] = fn.force - opt_.effective_stiffness() * delta * std::sqrt(delta);
    f_.noalias() += c.w_normal * fn.force;
    return fn;
  }

  // Eq. (10) on the slip rate gdot_T, added to f along W_T (none without friction).
  TangentForce tangent_force(int i, const ContactData& c, const NormalForce& fn) {
    TangentForce ft;
    if (c.friction > 0.0) {
      ft = regularized_coulomb(c.friction, fn.force, c.slip_rate(u_), opt_.stick_slip_velocity);
      lambda_t_[i] = ft.force;
      f_.noalias() += c.w_tangent * ft.force;
    }
    return ft;
  }

  // The contact's share of Jq_ = -dF/dq and Ju_ = -dF/du.
  void add_contact_jacobian(const ContactData& c, const NormalForce& fn, const TangentForce& ft) {
    // delta = -g_N with dg_N/dq = W_N^T, and deltadot = -(W_N^T u + what_N), so
    // dlambda_N/dq = -dF/ddelta W_N^T, dlambda_N/du = -dF/ddeltadot W_N^T.
    // The terms (dW_N/dq) u of dgdot/dq are left out: they are of the order of the
    // rotation rate times the damping force, small beside the stiffness terms, and a
    // Rosenbrock step with an approximate Jacobian stays consistent (the error control
    // sees the difference).
    Jq_.noalias() += fn.d_penetration * c.w_normal * c.w_normal.transpose();
    Ju_.noalias() += fn.d_rate * c.w_normal * c.w_normal.transpose();
    if (c.friction > 0.0) {
      Jq_.noalias() += (ft.d_normal * fn.d_penetration) * c.w_tangent * c.w_normal.transpose();
      Ju_.noalias() += (ft.d_normal * fn.d_rate) * c.w_tangent * c.w_normal.transpose();
      Ju_.noalias() -= ft.d_slip * c.w_tangent * c.w_tangent.transpose();
    }
  }

  // dx/dt = (u, M^-1 (f + F)).
  void rhs(const State& x, State& dxdt, double t) {
    evaluate(t, x, false);
    acc_.noalias() = minv_ * f_;
    dxdt.head(n_) = u_;
    dxdt.tail(n_) = acc_;
  }

  // At the start of a step: dxdt = f(t, x) and the Jacobian
  // J = [0, I; -M^-1 (K + Jq), -M^-1 (C + Ju)], with dfdt by a forward difference in t. One
  // evaluation of the system serves both f and the contact derivatives.
  void rhs_and_jacobian(const State& x, double t, State& dxdt, JacobianMatrix& J,
                        State& dfdt) {
    evaluate(t, x, true);
    acc_.noalias() = minv_ * f_;
    dxdt.head(n_) = u_;
    dxdt.tail(n_) = acc_;
    sys_.tangent(t, q_, u_, K_, C_);
    K_ += Jq_;
    C_ += Ju_;
    J.topLeftCorner(n_, n_).setZero();
    J.topRightCorner(n_, n_).setIdentity();
    J.bottomLeftCorner(n_, n_).noalias() = -minv_ * K_;
    J.bottomRightCorner(n_, n_).noalias() = -minv_ * C_;
    const double ht = kTimeDifferenceStep * std::max(1.0, std::abs(t));
    rhs(x, dfdt, t + ht);
    dfdt = (dfdt - dxdt) / ht;
  }

  // Gaps at the cubic Hermite interpolant of q (and the linear one of u) at t0 + s h: the
  // normal fields (gap_normal, far) of a buffer of their own, so that the contact data of
  // the last evaluated state stay as they are.
  const std::vector<ContactData>& gaps_at(double t0, const State& x0, double t1,
                                          const State& x1, double s) {
    const double h = t1 - t0;
    const Hermite b(s);
    q_ = b.h00 * x0.head(n_) + (b.h10 * h) * x0.tail(n_) + b.h01 * x1.head(n_) +
         (b.h11 * h) * x1.tail(n_);
    u_ = (1.0 - s) * x0.tail(n_) + s * x1.tail(n_);
    sys_.contact_normals(t0 + s * h, q_, u_, probes_);
    return probes_;
  }

  System& sys_;
  ComplianceOptions opt_;
  int n_, m_;
  Matrix minv_;
  Vector q_, u_, f_, acc_;
  Matrix K_, C_, Jq_, Ju_;
  std::vector<ContactData> contacts_, probes_;
  Vector lambda_n_, lambda_t_, damping_part_;
  Vector chi_, v_minus_;
};

bool finite(const State& x) { return x.allFinite(); }

// Energy flows at one state, for the trapezoidal accumulation of the balance.
struct Powers {
  double external = 0, ground = 0, damping = 0, impacts = 0, friction = 0;
};

// One integration of the compliance method, split along §4 of the paper: the gap elements'
// state (closure and approach velocity v_minus, which fix eq. 9's damping), the step with its
// control (Rosenbrock step, closures located on the step's interpolant so that contact onset
// is a step boundary), the events, and the energy balance.
class ComplianceRun {
 public:
  ComplianceRun(System& system, const ComplianceOptions& options, Recorder& recorder,
                const Progress& progress)
      : system_(system), options_(options), recorder_(recorder),
        book_(ComplianceOptions::kMethod, progress, kProgressInterval),
        core_(system, options),
        n_(core_.dofs()), m_(core_.contacts()),
        closed_(static_cast<std::size_t>(m_), 0), pending_(static_cast<std::size_t>(m_), 0),
        stepper_(core_, 2 * core_.dofs(), options.tolerance, options.tolerance, options.max_step) {}

  RunResult integrate() {
    RunResult& stats = book_.result();
    start();
    double dt = std::min(options_.initial_step, options_.max_step);
    const double time_scale = std::max(1.0, std::abs(options_.end_time));
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
      book_.progress_at_interval(t_);
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

 private:
  // Where the step's interpolant first closes an open gap.
  struct Closure {
    bool retake = false;    // the closure is inside the step: retake it up to `time`
    bool at_start = false;  // the closure is at the start of the step: close the pending now
    double time = 0.0;
  };

  // Initial state, eq. (9)'s damping factor chi of every contact from its restitution, the
  // contacts closed at t0, the initial energy and the first sample.
  void start() {
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
    recorder_.sample(t_, core_.q_, core_.u_, core_.contacts_, core_.lambda_n_, core_.lambda_t_,
                     0.0);
    start_gap_ = Vector::Zero(m_);
    start_rate_ = Vector::Zero(m_);
    remember_start();
  }

  // A gap element closes: eq. (9)'s v_minus is the approach velocity now (floored).
  void close_contact(int i, double time) {
    const ContactData& c = core_.contacts_[static_cast<std::size_t>(i)];
    closed_[static_cast<std::size_t>(i)] = 1;
    core_.v_minus_[i] = std::max(-c.gap_rate(core_.u_), options_.min_impact_velocity);
    recorder_.event(time, i + 1, EventKind::kClose);
  }

  // Contacts whose closure the search looks for: open at the start of the step, not far, and
  // not already located (on a step that landed on a located closure).
  bool searched(int i, const ContactData& c, bool landed) const {
    const auto ii = static_cast<std::size_t>(i);
    return !closed_[ii] && !c.far && !(landed && pending_[ii]);
  }

  // Smallest searched gap on the interpolant at t + s (t_new - t).
  double min_open_gap(double t_new, bool landed, double s) {
    double g = std::numeric_limits<double>::infinity();
    const auto& cs = core_.gaps_at(t_, x_, t_new, xnew_, s);
    for (int i = 0; i < m_; ++i) {
      const ContactData& c = cs[static_cast<std::size_t>(i)];
      if (searched(i, c, landed)) g = std::min(g, c.gap_normal);
    }
    return g;
  }

  // The gaps and gap rates at the accepted state, the start of the next step (may_close()).
  void remember_start() {
    for (int i = 0; i < m_; ++i) {
      const ContactData& c = core_.contacts_[static_cast<std::size_t>(i)];
      start_gap_[i] = c.gap_normal;
      start_rate_[i] = c.gap_rate(core_.u_);
    }
  }

  // Whether a gap the search looks for may close within the step: false when every one stays
  // open by the bound of closure_bound.hpp on its values and rates at the step's two ends, so
  // that the probes, which would all find it open, are skipped.
  bool may_close(double t_new, bool landed) {
    const auto& cs = core_.gaps_at(t_, x_, t_new, xnew_, 1.0);
    for (int i = 0; i < m_; ++i) {
      const auto ii = static_cast<std::size_t>(i);
      if (closed_[ii] || (landed && pending_[ii])) continue;
      if (!gap_stays_open(start_gap_[i], start_rate_[i], cs[ii].gap_normal,
                          cs[ii].gap_rate(core_.u_), t_new - t_)) {
        return true;
      }
    }
    return false;
  }

  // Step control at contact onset: the first probe point where a searched gap is negative,
  // then bisection on the interpolant between it and the previous probe. The contacts that
  // close first become pending.
  Closure locate_closure(double t_new, bool landed) {
    Closure out;
    if (m_ == 0 || !may_close(t_new, landed)) return out;
    double s_lo = 0.0, s_hi = -1.0;
    for (int j = 1; m_ > 0 && j <= kClosureProbes; ++j) {
      const double s = static_cast<double>(j) / kClosureProbes;
      if (min_open_gap(t_new, landed, s) < 0.0) {
        s_hi = s;
        s_lo = static_cast<double>(j - 1) / kClosureProbes;
        break;
      }
    }
    if (!(s_hi > 0.0)) return out;
    for (int it = 0; it < kMaxBisections && s_hi - s_lo > kClosureRelativeWidth; ++it) {
      const double mid = 0.5 * (s_lo + s_hi);
      (min_open_gap(t_new, landed, mid) < 0.0 ? s_hi : s_lo) = mid;
    }
    const double t_close = t_ + s_lo * (t_new - t_);
    // The contacts that close first: their interpolated gap at s_hi is negative.
    const auto& cs = core_.gaps_at(t_, x_, t_new, xnew_, s_hi);
    std::fill(pending_.begin(), pending_.end(), 0);
    for (int i = 0; i < m_; ++i) {
      const ContactData& c = cs[static_cast<std::size_t>(i)];
      if (searched(i, c, landed) && c.gap_normal < 0.0) pending_[static_cast<std::size_t>(i)] = 1;
    }
    if (t_close - t_ > 10.0 * kMinRelativeStep * std::max(1.0, std::abs(t_))) {
      out.retake = true;
      out.time = t_close;
    } else {
      out.at_start = true;
    }
    return out;
  }

  // Openings: a closed gap that is positive at the end of the step; the crossing is located
  // on the interpolant for the event time only (the force is continuous there).
  void record_openings(double t_new) {
    const double h = t_new - t_;
    for (int i = 0; i < m_; ++i) {
      const auto ii = static_cast<std::size_t>(i);
      if (!closed_[ii]) continue;
      if (!(core_.gaps_at(t_, x_, t_new, xnew_, 1.0)[ii].gap_normal > 0.0)) continue;
      double lo = 0.0, hi = 1.0;
      for (int it = 0; it < kMaxBisections && hi - lo > kClosureRelativeWidth; ++it) {
        const double mid = 0.5 * (lo + hi);
        (core_.gaps_at(t_, x_, t_new, xnew_, mid)[ii].gap_normal > 0.0 ? hi : lo) = mid;
      }
      closed_[ii] = 0;
      recorder_.event(t_ + hi * h, i + 1, EventKind::kOpen);
    }
  }

  // Closures at the new time: a negative gap, or a located closure this step landed on.
  // Returns whether any contact closed.
  bool record_closures(bool landed, bool close_at_start) {
    bool closed_now = false;
    for (int i = 0; i < m_; ++i) {
      const auto ii = static_cast<std::size_t>(i);
      const ContactData& c = core_.contacts_[ii];
      if (closed_[ii] || c.far) {
        pending_[ii] = 0;
        continue;
      }
      if (c.gap_normal < 0.0 || (pending_[ii] && (landed || close_at_start))) {
        close_contact(i, t_);
        pending_[ii] = 0;
        closed_now = true;
      }
    }
    return closed_now;
  }

  // Accepts the step to t_new: events, commit, energy, the step handed to the system
  // (watch()), sample. False when the system stopped the run (unseated).
  bool accept_step(double t_new, bool landed, bool close_at_start) {
    record_openings(t_new);
    const double h = t_new - t_;
    x_ = xnew_;
    t_ = t_new;
    book_.count_step();
    core_.evaluate(t_, x_, false, ContactFields::kAll);
    system_.commit();
    const bool closed_now = record_closures(landed, close_at_start);
    if (landed) {
      target_ = std::numeric_limits<double>::infinity();
      std::fill(pending_.begin(), pending_.end(), 0);
    }
    // The forces with the new v_minus, for the record.
    if (closed_now) core_.evaluate(t_, x_, false, ContactFields::kAll);
    const StepVerdict verdict = watch(h);
    accumulate_energy(h);
    recorder_.sample(t_, core_.q_, core_.u_, core_.contacts_, core_.lambda_n_, core_.lambda_t_,
                     energy_.error);
    remember_start();
    if (verdict != StepVerdict::kUnseated) return true;
    book_.unseat(t_);
    book_.result().message = "unseated at t = " + format_number(t_) + " s";
    return false;
  }

  // System::accept_step with the step's normal impulses: the law's force (eq. 9) integrated
  // by the trapezoidal rule over the step of length h. A contact the system removed is far
  // from now on: its gap element opens (an "open" event) and carries no force.
  StepVerdict watch(double h) {
    for (int i = 0; i < m_; ++i) {
      impulse_[i] = 0.5 * h * (lambda_start_[i] + core_.lambda_n_[i]);
    }
    accepted_.t = t_;
    accepted_.h = h;
    const StepVerdict verdict = system_.accept_step(accepted_);
    if (verdict == StepVerdict::kContactsRemoved) {
      record_removed_contacts(system_, t_, recorder_);
      core_.evaluate(t_, x_, false, ContactFields::kAll);
      for (int i = 0; i < m_; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        if (!core_.contacts_[ii].far) continue;
        pending_[ii] = 0;
        if (closed_[ii]) recorder_.event(t_, i + 1, EventKind::kOpen);
        closed_[ii] = 0;
      }
    }
    lambda_start_ = core_.lambda_n_;
    return verdict;
  }

  // Energy stored in the Hertz springs: integral of k delta^1.5 = 0.4 k delta^2.5.
  double contact_potential() const {
    double v = 0.0;
    for (const ContactData& c : core_.contacts_) {
      if (!c.far && c.gap_normal < 0.0) v += 0.4 * options_.effective_stiffness() * std::pow(-c.gap_normal, 2.5);
    }
    return v;
  }

  // Energy flows at the current state.
  Powers powers() const {
    Powers p;
    const PowerTerms s = system_.power(t_, core_.q_, core_.u_);
    p.external = s.external;
    p.ground = s.ground;
    p.damping = s.damping;
    for (int i = 0; i < m_; ++i) {
      const ContactData& c = core_.contacts_[static_cast<std::size_t>(i)];
      // Work of the contact forces on the system: lambda (W^T u) = lambda (gdot - what).
      // The spring part of lambda_N is stored energy (contact_potential); the rest of the
      // normal work is the dissipation of the dashpot; the what-terms are work done by
      // moving obstacles (ground).
      p.impacts += core_.damping_part_[i] * c.gap_rate(core_.u_);
      p.ground -= core_.lambda_n_[i] * c.what_normal + core_.lambda_t_[i] * c.what_tangent;
      p.friction += core_.lambda_t_[i] * c.slip_rate(core_.u_);
    }
    return p;
  }

  void update_state_energy() {
    momentum_.noalias() = system_.mass() * core_.u_;  // M u, in a buffer sized once
    energy_.kinetic = 0.5 * core_.u_.dot(momentum_);
    const EnergyState es = system_.energy(t_, core_.q_);
    energy_.stored = es.stored + contact_potential();
    energy_.hysteretic = es.hysteretic;
  }

  // The balance terms by the trapezoidal rule over the accepted step of length h.
  void accumulate_energy(double h) {
    const Powers p_new = powers();
    energy_.external += 0.5 * h * (p_old_.external + p_new.external);
    energy_.ground += 0.5 * h * (p_old_.ground + p_new.ground);
    energy_.damping += 0.5 * h * (p_old_.damping + p_new.damping);
    energy_.impacts += 0.5 * h * (p_old_.impacts + p_new.impacts);
    energy_.friction += 0.5 * h * (p_old_.friction + p_new.friction);
    p_old_ = p_new;
    update_state_energy();
    energy_.close();
  }

  System& system_;
  const ComplianceOptions& options_;
  Recorder& recorder_;
  RunBookkeeping book_;
  Core core_;
  int n_, m_;
  // Per-contact state of the gap elements: closed, and located to close at the target time.
  std::vector<char> closed_, pending_;
  Rosenbrock4<Core> stepper_;
  EnergyBalance energy_;
  Powers p_old_;
  double t_ = 0.0;
  double target_ = std::numeric_limits<double>::infinity();  // closure time to land on
  State x_, xnew_;
  Vector momentum_;
  // The step's normal impulses [kN s] and lambda_N at the step's start [kN] (watch()).
  Vector impulse_, lambda_start_;
  Vector start_gap_, start_rate_;  // gaps [m] and gap rates [m/s] at t_ (remember_start())
  AcceptedStep accepted_;
};

}  // namespace

RunResult compliance(System& system, const ComplianceOptions& options, Recorder& recorder,
                     const Progress& progress) {
  options.validate();
  if (!(options.end_time > system.initial_time())) {
    throw std::invalid_argument("compliance options: end_time: must be > the initial time");
  }
  ComplianceRun run(system, options, recorder, progress);
  return run.integrate();
}

}  // namespace nsb::integrators