// The compliance method's integrator (compliance.hpp), shared by the files that implement it,
// one concern each, as the event-driven method is split (event_integrator.hpp):
//   compliance.cpp          the entry, the step loop and the initial state
//   compliance_forces.cpp   the right-hand side: the contact forces of eqs. (9) and (10), their
//                           Jacobian, the gaps on a step's interpolant
//   compliance_closure.cpp  the gap elements: closures located on the step's interpolant, and
//                           the openings and closures recorded as events
//   compliance_accept.cpp   accepting a step: the system's accept_step, the energy balance and
//                           the recorder's samples
//   compliance_laws.cpp     eqs. (9) and (10) and the damping laws
#pragma once

#include "integrators/compliance.hpp"
#include "integrators/rosenbrock.hpp"
#include "integrators/run_bookkeeping.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace nsb::integrators::compliance_detail {

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
inline const double kTimeDifferenceStep = std::sqrt(std::numeric_limits<double>::epsilon());
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
  Core(System& system, const ComplianceOptions& o);

  int dofs() const { return n_; }
  int contacts() const { return m_; }

  // Loads q, u from x and evaluates f, the contact data and the contact forces at (t, q, u).
  // With derivatives, also fills Jq_ = -dF/dq and Ju_ = -dF/du of the generalized contact
  // force F = sum W_N lambda_N + W_T lambda_T (geometric terms dW/dq neglected: see below).
  // `data` says which contact fields must be current afterwards (ContactFields).
  void evaluate(double t, const State& x, bool derivatives,
                ContactFields data = ContactFields::kForces);

  // Gaps, W and the rheonomic terms (eq. 2) at (t, q_, u_). For the forces alone the normal
  // part comes first (System::contact_normals, the same numbers for a fraction of the work):
  // eqs. (9) and (10) act only on penetrated contacts, so the full data are needed only when
  // one is; while every gap is open the tangential fields keep stale values nobody reads.
  void load_contacts(double t, ContactFields data);

  // Eq. (9) on the penetration delta = -g_N and its rate -gdot_N, added to f along W_N.
  NormalForce normal_force(int i, const ContactData& c);

  // Eq. (10) on the slip rate gdot_T, added to f along W_T (none without friction).
  TangentForce tangent_force(int i, const ContactData& c, const NormalForce& fn);

  // The contact's share of Jq_ = -dF/dq and Ju_ = -dF/du.
  void add_contact_jacobian(const ContactData& c, const NormalForce& fn, const TangentForce& ft);

  // dx/dt = (u, M^-1 (f + F)).
  void rhs(const State& x, State& dxdt, double t);

  // At the start of a step: dxdt = f(t, x) and the Jacobian
  // J = [0, I; -M^-1 (K + Jq), -M^-1 (C + Ju)], with dfdt by a forward difference in t. One
  // evaluation of the system serves both f and the contact derivatives.
  void rhs_and_jacobian(const State& x, double t, State& dxdt, JacobianMatrix& J,
                        State& dfdt);

  // Gaps at the cubic Hermite interpolant of q (and the linear one of u) at t0 + s h: the
  // normal fields (gap_normal, far) of a buffer of their own, so that the contact data of
  // the last evaluated state stay as they are.
  const std::vector<ContactData>& gaps_at(double t0, const State& x0, double t1,
                                          const State& x1, double s);

  System& sys_;
  ComplianceOptions opt_;
  int n_, m_;
  Matrix minv_;
  Vector q_, u_, f_, acc_;
  // The smooth force f alone (evaluate() adds the contact forces to f_), kept only when it
  // has a size: the recorder's output group "forces" reads it (empty otherwise, no work).
  Vector f_smooth_;
  Matrix K_, C_, Jq_, Ju_;
  std::vector<ContactData> contacts_, probes_;
  Vector lambda_n_, lambda_t_, damping_part_;
  Vector chi_, v_minus_;
};

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
        stepper_(core_, 2 * core_.dofs(), options.tolerance, options.tolerance, options.max_step) {
    // core_.f_smooth_ is f at every recorded state: each is evaluated (Core::evaluate) before
    // it is handed to the recorder.
    if (recorder.groups().has(OutputGroup::kForces)) core_.f_smooth_ = Vector::Zero(n_);
    recorder_.watch(&energy_, &core_.f_smooth_);
    if (recorder.groups().has(OutputGroup::kImpulses)) {
      episode_event_.assign(static_cast<std::size_t>(m_), -1);
      episode_ends_.assign(static_cast<std::size_t>(m_), 0);
      episode_impact_.assign(static_cast<std::size_t>(m_), 0);
      episode_normal_ = Vector::Zero(m_);
      episode_tangent_ = Vector::Zero(m_);
      lambda_t_start_ = Vector::Zero(m_);
    }
  }

  // Reads stop (may be nullptr) at every accepted step: RunBookkeeping::watch.
  void watch(const std::atomic<bool>* stop) { book_.watch(stop); }

  // The run from the system's initial state to end_time, or to the first stop.
  RunResult integrate();

 private:
  // Where the step's interpolant first closes an open gap.
  struct Closure {
    bool retake = false;    // the closure is inside the step: retake it up to `time`
    bool at_start = false;  // the closure is at the start of the step: close the pending now
    double time = 0.0;
  };

  // Initial state, eq. (9)'s damping factor chi of every contact from its restitution, the
  // contacts closed at t0, the initial energy and the first sample.
  void start();

  // A gap element closes: eq. (9)'s v_minus is the approach velocity now (floored).
  void close_contact(int i, double time);

  // Contacts whose closure the search looks for: open at the start of the step, not far, and
  // not already located (on a step that landed on a located closure).
  bool searched(int i, const ContactData& c, bool landed) const;

  // Smallest searched gap on the interpolant at t + s (t_new - t).
  double min_open_gap(double t_new, bool landed, double s);

  // The gaps and gap rates at the accepted state, the start of the next step (may_close()).
  void remember_start();

  // Whether a gap the search looks for may close within the step: false when every one stays
  // open by the bound of closure_bound.hpp on its values and rates at the step's two ends, so
  // that the probes, which would all find it open, are skipped.
  bool may_close(double t_new, bool landed);

  // Step control at contact onset: the first probe point where a searched gap is negative,
  // then bisection on the interpolant between it and the previous probe. The contacts that
  // close first become pending.
  Closure locate_closure(double t_new, bool landed);

  // Openings: a closed gap that is positive at the end of the step; the crossing is located
  // on the interpolant for the event time only (the force is continuous there).
  void record_openings(double t_new);

  // Closures at the new time: a negative gap, or a located closure this step landed on.
  // Returns whether any contact closed.
  bool record_closures(bool landed, bool close_at_start);

  // Accepts the step to t_new: events, commit, energy, the step handed to the system
  // (watch()), sample. False when the system stopped the run (unseated).
  bool accept_step(double t_new, bool landed, bool close_at_start);

  // System::accept_step with the step's normal impulses: the law's force (eq. 9) integrated
  // by the trapezoidal rule over the step of length h. A contact the system removed is far
  // from now on: its gap element opens (an "open" event) and carries no force.
  StepVerdict watch(double h);

  // Energy stored in the Hertz springs: integral of k delta^1.5 = 0.4 k delta^2.5.
  double contact_potential() const;

  // Energy flows at the current state.
  Powers powers() const;

  void update_state_energy();

  // The balance terms by the trapezoidal rule over the accepted step of length h.
  void accumulate_energy(double h);

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
  // OutputGroup::kImpulses (empty otherwise): per contact, the index in the recorder's events
  // of the "close" that began its contact episode (-1: none), whether an "impact" row
  // precedes that "close" (the episode is an impact), whether the episode ended in the step
  // being accepted, the episode's normal and tangential impulses so far [kN s]
  // (trapezoidal rule over the accepted steps, as impulse_) and lambda_T at the step's start.
  std::vector<std::ptrdiff_t> episode_event_;
  std::vector<char> episode_impact_;
  std::vector<char> episode_ends_;
  Vector episode_normal_, episode_tangent_, lambda_t_start_;
  void add_episode_impulses(double h);
  Vector start_gap_, start_rate_;  // gaps [m] and gap rates [m/s] at t_ (remember_start())
  AcceptedStep accepted_;
};

}  // namespace nsb::integrators::compliance_detail
