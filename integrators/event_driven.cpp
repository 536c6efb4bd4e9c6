#include "integrators/event_driven.hpp"

#include "integrators/contact_stage.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

// Only the Odeint parts used here: <boost/numeric/odeint.hpp> pulls in uBLAS, which does not
// compile as C++20.
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/dense_output_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace nsb::integrators {

namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;
using Dopri = odeint::runge_kutta_dopri5<State>;
using Dense = odeint::result_of::make_dense_output<Dopri>::type;

// The mode of one contact during a smooth phase is an integrators::ContactState
// (contact_stage.hpp), shared with Moreau–Jean. A closed contact slides with the sign of its
// slip velocity (kSlipPositive / kSlipNegative), or is kClosed when frictionless.
ContactState slip_state(double sign) {
  return sign > 0.0 ? ContactState::kSlipPositive
                    : sign < 0.0 ? ContactState::kSlipNegative : ContactState::kClosed;
}

// Integrated energy terms appended to (q, u) in the Odeint state, so that the energy balance
// is integrated to the same tolerance as the motion.
enum EnergyIndex { kDamping = 0, kGround, kExternal, kNormal, kFriction, kEnergyTerms };

// Relative size of the shifts that make "reaches 0" a strict sign change of an indicator
// (lambda_N + shift, s gdot_T + shift): far below any tolerance a user can ask for, but
// large enough that an indicator which starts a phase at round-off zero does not fire.
constexpr double kIndicatorShift = 1e-10;
// Iterations of the Newton projection onto g_N = 0 (the gaps are near-linear in q over the
// drift corrected, so two or three iterations reach round-off).
constexpr int kProjectionIterations = 4;
// Brent iterations; the bracket halves at least every few iterations, so 200 is ample for
// any step down to event_time_tolerance.
constexpr int kBrentIterations = 200;
// Relative margin below which |lambda_T| counts as on the friction cone mu lambda_N: the
// contact LCP is solved to 1e-12.
constexpr double kConeSaturation = 1e-9;
// Default gap_tolerance [m]: closed contacts are projected back once they drift further, and
// open contacts count as touching at an event within it. An absolute length, not a multiple
// of the (relative) tolerance: at tolerance 1e-3 that would be 1 cm, the size of the gaps.
constexpr double kDefaultGapTolerance = 1e-9;
// A normal force below this fraction of the applied forces' scale is round-off of the
// contact LCP (solved to 1e-12): the contact is not held closed by it.
constexpr double kClosedForce = 1e-12;
// Accepted steps between two calls of the progress callback.
constexpr std::int64_t kProgressInterval = 1024;

class EventDriven {
 public:
  EventDriven(System& system, const EventDrivenOptions& options, Recorder& recorder,
              const Progress& progress)
      : sys_(system), opt_(options), rec_(recorder), progress_(progress) {
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
    phase_b_ = Matrix::Zero(n_, 2 * m_);
    phase_r_ = Matrix::Zero(n_, 2 * m_);
    phase_rt_minv_ = Matrix::Zero(2 * m_, n_);
    phase_wbar_ = Vector::Zero(2 * m_);
    phase_a_free_ = Vector::Zero(n_);
    phase_lambda_ = Vector::Zero(2 * m_);
    phase_b_lambda_ = Vector::Zero(n_);
    xs_.assign(static_cast<std::size_t>(2 * n_ + kEnergyTerms), 0.0);
    stats_.method = "event_driven";
    ContactStageOptions stage_options;
    stage_options.solver = opt_.solver;
    stage_options.tolerance = opt_.lcp_tolerance;
    stage_ = ContactStage(n_, m_, stage_options);
    touching_.reserve(static_cast<std::size_t>(m_));
    candidates_.reserve(static_cast<std::size_t>(m_));
    slip_coupling_.assign(static_cast<std::size_t>(m_), 0.0);
    u_plus_ = Vector::Zero(n_);
    q_event_ = Vector::Zero(n_);
    u_event_ = Vector::Zero(n_);
    a_free_ = Vector::Zero(n_);
  }

  RunResult run();

 private:
  // ---- state helpers ----
  void unpack(const State& x, Vector& q, Vector& u) const {
    for (int i = 0; i < n_; ++i) {
      q[i] = x[static_cast<std::size_t>(i)];
      u[i] = x[static_cast<std::size_t>(n_ + i)];
    }
  }
  double energy_term(const State& x, int k) const {
    return x[static_cast<std::size_t>(2 * n_ + k)];
  }
  static std::size_t idx(int i) { return static_cast<std::size_t>(i); }

  // Accelerations and contact forces with the modes of the current phase held fixed:
  //   M udot = f + sum_closed B_i lambda_N,i + sum_stick W_T,i lambda_T,i
  // with B_i = W_N,i for sticking and B_i = W_N,i - mu_i s_i W_T,i for sliding contacts, and
  // the constraints gddot_N,i = W_N,i^T udot + wbar_N,i = 0 (closed) and
  // gddot_T,i = W_T,i^T udot + wbar_T,i = 0 (sticking). Redundant constraints (four corners
  // closed on a three-DOF deck) give a singular system; its minimum-norm solution is one
  // admissible distribution of the forces.
  // The reduced system of the closed contacts, A lambda = rhs with A = (R^T M^-1) B, by a
  // complete orthogonal decomposition (A is singular when closed contacts are redundant), and
  // udot = a_free + M^-1 (B lambda). Up to kSmallClosed unknowns the matrices have fixed
  // maximum sizes (storage inside the objects), so the decomposition and its solve allocate
  // nothing; the larger case keeps one workspace whose size changes only with k.
  template <class SquareMatrix>
  void solve_closed(int k, SquareMatrix& a,
                    Eigen::CompleteOrthogonalDecomposition<SquareMatrix>& cod) {
    using Column =
        Eigen::Matrix<double, Eigen::Dynamic, 1, 0, SquareMatrix::MaxRowsAtCompileTime, 1>;
    a.resize(k, k);
    a.noalias() = phase_rt_minv_.topRows(k) * phase_b_.leftCols(k);
    Column rhs(k);
    rhs.noalias() = phase_r_.leftCols(k).transpose() * phase_a_free_;
    rhs = -(rhs + phase_wbar_.head(k));
    cod.compute(a);
    const Column lambda = cod.solve(rhs);
    phase_lambda_.head(k) = lambda;
    phase_b_lambda_.noalias() = phase_b_.leftCols(k) * lambda;
    udot_ = phase_a_free_;
    udot_.noalias() += minv_ * phase_b_lambda_;
  }

  void phase_forces(double t, const Vector& q, const Vector& u) {
    sys_.forces(t, q, u, f_);
    lambda_n_.setZero();
    lambda_t_.setZero();
    int k = 0;
    for (const auto& md : modes_) {
      if (closed(md)) ++k;
      if (md == ContactState::kStick) ++k;
    }
    if (k == 0) {
      udot_.noalias() = minv_ * f_;
      return;
    }
    sys_.contact_data(t, q, u, cbuf_);
    // Columns of the closed contacts into the workspace sized once for every contact (n x 2m):
    // the right-hand side of every smooth-phase step runs this, so nothing here allocates.
    auto B = phase_b_.leftCols(k);
    auto R = phase_r_.leftCols(k);
    int j = 0;
    for (int i = 0; i < m_; ++i) {
      const auto& md = modes_[idx(i)];
      const auto& c = cbuf_[idx(i)];
      if (!closed(md)) continue;
      R.col(j) = c.w_normal;
      B.col(j) = c.w_normal;
      if (sliding(md)) {
        B.col(j) -= c.friction * slip_sign(md) * c.w_tangent;
      }
      phase_wbar_[j] = c.wbar_normal;
      ++j;
      if (md == ContactState::kStick) {
        R.col(j) = c.w_tangent;
        B.col(j) = c.w_tangent;
        phase_wbar_[j] = c.wbar_tangent;
        ++j;
      }
    }
    phase_a_free_.noalias() = minv_ * f_;
    // A = (R^T M^-1) B and rhs = -(R^T a_free + wbar), evaluated in that order.
    auto rt_minv = phase_rt_minv_.topRows(k);
    rt_minv.noalias() = R.transpose() * minv_;
    if (k <= kSmallClosed) {
      solve_closed(k, phase_small_, phase_small_cod_);
    } else {
      solve_closed(k, phase_large_, phase_large_cod_);
    }
    j = 0;
    for (int i = 0; i < m_; ++i) {
      const auto& md = modes_[idx(i)];
      if (!closed(md)) continue;
      lambda_n_[i] = phase_lambda_[j++];
      if (md == ContactState::kStick) {
        lambda_t_[i] = phase_lambda_[j++];
      } else if (sliding(md)) {
        lambda_t_[i] = -cbuf_[idx(i)].friction * slip_sign(md) * lambda_n_[i];
      }
    }
  }

  // The right-hand side of the smooth phase: d/dt (q, u, energies).
  void rhs(const State& x, State& dxdt, double t) {
    ++rhs_evaluations_;
    unpack(x, q_, u_);
    if (!q_.allFinite() || !u_.allFinite()) {
      // Never hand a non-finite state to the system: the step that produced it is reported
      // as divergence once Odeint returns (run()).
      std::fill(dxdt.begin(), dxdt.end(), std::numeric_limits<double>::quiet_NaN());
      return;
    }
    phase_forces(t, q_, u_);
    for (int i = 0; i < n_; ++i) {
      dxdt[idx(i)] = u_[i];
      dxdt[idx(n_ + i)] = udot_[i];
    }
    const PowerTerms p = sys_.power(t, q_, u_);
    // The power of a contact force on the system, lambda W^T u = lambda (gdot - what), splits
    // into the power in the contact, lambda gdot (<= 0: zero when closed or sticking,
    // -mu lambda_N |gdot_T| when sliding), and the power of the moving seat, -lambda what,
    // which is energy put in through support motion.
    double normal = 0.0, friction = 0.0, seat = 0.0;
    bool any_closed = false;
    for (const auto& md : modes_) any_closed = any_closed || closed(md);
    if (any_closed) {
      for (int i = 0; i < m_; ++i) {
        if (!closed(modes_[idx(i)])) continue;
        const auto& c = cbuf_[idx(i)];
        normal += lambda_n_[i] * c.gap_rate(u_);
        friction += lambda_t_[i] * c.slip_rate(u_);
        seat -= lambda_n_[i] * c.what_normal + lambda_t_[i] * c.what_tangent;
      }
    }
    dxdt[idx(2 * n_ + kDamping)] = p.damping;
    dxdt[idx(2 * n_ + kGround)] = p.ground + seat;
    dxdt[idx(2 * n_ + kExternal)] = p.external;
    dxdt[idx(2 * n_ + kNormal)] = normal;
    dxdt[idx(2 * n_ + kFriction)] = friction;
  }

  // Event indicators at (t, x): h[2i] is g_N (open) or lambda_N + shift (closed); h[2i+1] is
  // s gdot_T + shift (sliding with friction), mu lambda_N - |lambda_T| + shift (sticking),
  // or +1 (no tangential event possible). An event is a sign change from >= 0 to < 0.
  void indicators(double t, const State& x) {
    unpack(x, q_, u_);
    if (!q_.allFinite() || !u_.allFinite()) {
      h_.setOnes();  // no event in a non-finite state: run() stops on it as divergence
      return;
    }
    phase_forces(t, q_, u_);
    sys_.contact_data(t, q_, u_, cbuf_);
    for (int i = 0; i < m_; ++i) {
      const auto& c = cbuf_[idx(i)];
      const auto& md = modes_[idx(i)];
      switch (md) {
        case ContactState::kOpen:
          h_[2 * i] = c.gap_normal;
          h_[2 * i + 1] = 1.0;
          break;
        case ContactState::kStick:
          h_[2 * i] = lambda_n_[i] + force_shift_;
          h_[2 * i + 1] = c.friction * lambda_n_[i] - std::abs(lambda_t_[i]) + force_shift_;
          break;
        case ContactState::kClosed:
          h_[2 * i] = lambda_n_[i] + force_shift_;
          h_[2 * i + 1] = 1.0;
          break;
        case ContactState::kSlipPositive:
        case ContactState::kSlipNegative:
          h_[2 * i] = lambda_n_[i] + force_shift_;
          h_[2 * i + 1] = slip_sign(md) * c.slip_rate(u_) + velocity_shift_;
          break;
      }
    }
  }
  double indicator_at(double t, int k) {
    dense_.calc_state(t, xs_);
    indicators(t, xs_);
    return h_[k];
  }
  double gap_rate_at(double t, int i) {
    dense_.calc_state(t, xs_);
    unpack(xs_, q_, u_);
    sys_.contact_data(t, q_, u_, cbuf_);
    return cbuf_[idx(i)].gap_rate(u_);
  }

  // Brent's method (GSL) on fun over [a, b] with fun(a) >= 0 > fun(b). Returns the upper end
  // of the final bracket: the first time located past the crossing, to event_time_tolerance.
  template <class F>
  double brent(const F& fun, double a, double b) {
    if (!(b > a)) return b;
    struct Thunk {
      const F* f;
      static double call(double x, void* p) { return (*static_cast<const Thunk*>(p)->f)(x); }
    } thunk{&fun};
    gsl_function gf;
    gf.function = &Thunk::call;
    gf.params = &thunk;
    gsl_root_fsolver* s = brent_solver_.get();
    double lo = a, hi = b;
    if (gsl_root_fsolver_set(s, &gf, a, b) == GSL_SUCCESS) {
      for (int it = 0; it < kBrentIterations; ++it) {
        if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
        lo = gsl_root_fsolver_x_lower(s);
        hi = gsl_root_fsolver_x_upper(s);
        if (gsl_root_test_interval(lo, hi, opt_.event_time_tolerance, 0.0) == GSL_SUCCESS) break;
      }
    }
    // Keep the side past the crossing (Brent's bracket always straddles the root).
    if (fun(hi) >= 0.0 && fun(lo) < 0.0) return lo;
    return hi;
  }

  // Earliest event time in (ta, tb] for indicator k, or +inf. ha = indicator at ta.
  double locate(int k, double ta, double tb, double ha, double hb) {
    const double inf = std::numeric_limits<double>::infinity();
    const int i = k / 2;
    const bool gap = (k % 2 == 0) && !closed(modes_[idx(i)]);
    auto h = [this, k](double t) { return indicator_at(t, k); };
    if (!gap) {
      if (hb >= 0.0) return inf;
      if (ha < 0.0) return ta;
      return brent(h, ta, tb);
    }
    // An open contact: an impact when g_N goes below 0 while closing.
    auto gd = [this, i](double t) { return gap_rate_at(t, i); };
    const double va = gd(ta), vb = gd(tb);
    // A gap that is negative at tb fires only if it is closing faster than the Zeno
    // threshold there or has gone below -gap_shift_: a contact that touches without
    // closing (zero load, sliding along its face) stays open through round-off of g_N.
    const bool fires = hb < 0.0 && (hb < -gap_shift_ || vb < -closing_velocity_);
    if (ha > 0.0 && fires) return brent(h, ta, tb);
    if (ha <= 0.0 && fires) {
      // The contact has just been released at ta. If it rose and came back, locate the apex
      // (gdot_N = 0), then the crossing after it.
      if (va > 0.0 && vb < 0.0) {
        auto ngd = [&gd](double t) { return gd(t); };
        const double apex = brent(ngd, ta, tb);
        if (h(apex) > 0.0) return brent(h, apex, tb);
      }
      if (va > 0.0) return inf;
      // Released with gdot_N = 0 and gddot_N >= 0, but higher derivatives bring it back:
      // the event is where the penetration reaches gap_shift_.
      if (ha > -gap_shift_ && hb < -gap_shift_) {
        auto hs = [&h, this](double t) { return h(t) + gap_shift_; };
        return brent(hs, ta, tb);
      }
      return ta;
    }
    if (ha > 0.0 && hb >= 0.0 && va < 0.0 && vb > 0.0) {
      // Grazing inside the step: the gap has a minimum; test whether it dips below 0.
      auto neg_gd = [&gd](double t) { return -gd(t); };
      const double tmin = brent(neg_gd, ta, tb);
      if (h(tmin) < -gap_shift_) return brent(h, ta, tmin);
    }
    return inf;
  }

  // ---- events ----
  bool stage_failed(double t, int contact, ContactStatus status, const char* problem);
  void project_positions(double t, Vector& q, const Vector& u);
  void project_velocities(double t, const Vector& q, Vector& u);
  void book_impulses(const Matrix& W, const Vector& impulse, const Vector& what,
                     const std::vector<bool>& tangential, const Vector& u_minus,
                     const Vector& u_plus);
  void book_stage_impulses(const std::vector<int>& index, const Vector& u_minus,
                           const Vector& u_plus);
  bool zeno_guard(double t, int trigger_contact, bool initial, bool& forced);
  void find_touching(double t, const Vector& q, const Vector& u, bool initial, bool& any_impact);
  bool impact_problem(double t, Vector& u, bool forced, int trigger_contact);
  void closure_candidates(const Vector& u);
  bool contact_problem(double t, Vector& q, Vector& u);
  void record_mode_changes(double t, const std::vector<ContactState>& old);
  bool handle_event(double t, State& x, int trigger_contact, bool initial);
  void finish_counts();
  void record_sample(double t, const State& x, bool force);
  double balance_error(double t, const State& x);
  void warn(double t, int contact, const std::string& what) {
    rec_.event(t, contact, EventKind::kWarning, what);
    stats_.warnings.push_back("t = " + format_number(t) + " s, contact " +
                              std::to_string(contact) + ": " + what);
  }

  System& sys_;
  const EventDrivenOptions& opt_;
  Recorder& rec_;
  const Progress& progress_;
  ContactStage stage_;
  std::vector<int> touching_, candidates_;  // index sets of the impact and contact problems
  std::vector<double> slip_coupling_;       // -mu s of the contact problem's sliding contacts
  std::vector<ContactState> old_modes_;
  Vector u_plus_, a_free_, q_event_, u_event_;
  bool diverged_ = false, stalled_ = false;
  double first_unsolved_ = std::numeric_limits<double>::quiet_NaN();  // [s]
  int n_ = 0, m_ = 0;
  double closing_velocity_ = 0.0, stick_velocity_ = 0.0, gap_tolerance_ = 0.0;
  double gap_shift_ = 0.0;  // penetration [m] that fires an impact without a closing speed
  double force_shift_ = 0.0, velocity_shift_ = 0.0;
  Matrix minv_;
  std::vector<ContactData> cbuf_;
  std::vector<ContactState> modes_;
  Vector f_, q_, u_, udot_, lambda_n_, lambda_t_, h_;
  // Workspace of phase_forces: columns of the closed contacts, R^T M^-1, the reduced system.
  static constexpr int kSmallClosed = 8;  // unknowns (closed + sticking) of the fixed-size path
  using SmallSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kSmallClosed,
                                    kSmallClosed>;
  // Brent's root bracketing (GSL), allocated once: every event location reuses it.
  struct FsolverFree {
    void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
  };
  std::unique_ptr<gsl_root_fsolver, FsolverFree> brent_solver_{
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent)};
  Matrix phase_b_, phase_r_, phase_rt_minv_, phase_large_;
  Vector phase_wbar_, phase_a_free_, phase_lambda_, phase_b_lambda_;
  SmallSquare phase_small_;
  Eigen::CompleteOrthogonalDecomposition<SmallSquare> phase_small_cod_;
  Eigen::CompleteOrthogonalDecomposition<Matrix> phase_large_cod_;
  State xs_;
  Dense dense_ = odeint::make_dense_output(1e-8, 1e-8, Dopri());
  RunResult stats_;
  std::int64_t rhs_evaluations_ = 0;
  double impact_normal_work_ = 0.0, impact_friction_work_ = 0.0, impact_ground_work_ = 0.0;
  double initial_energy_ = 0.0;
  double next_sample_ = -std::numeric_limits<double>::infinity();
  std::deque<double> recent_events_;
  double forced_closure_until_ = -std::numeric_limits<double>::infinity();
  bool stop_ = false;
};

// Reports a contact problem the stage could not solve and says whether the run must stop:
// non-finite data is divergence; an unsolved problem stops the run (the phase that follows
// would rest on impulses or modes no solver confirmed).
bool EventDriven::stage_failed(double t, int contact, ContactStatus status, const char* problem) {
  if (status == ContactStatus::kSolved || status == ContactStatus::kSolvedByFallback) return false;
  if (status == ContactStatus::kNonFiniteInput) {
    diverged_ = true;
    stats_.message = std::string(problem) + ": non-finite data at t = " + format_number(t) + " s";
  } else {
    const lcp::FrictionalResult& r = stage_.result();
    stats_.message = std::string(problem) + " not solved by any solver of the chain at t = " +
                     format_number(t) + " s (last: " +
                     std::string(lcp::to_string(r.solver_used)) + ", " +
                     std::string(lcp::to_string(r.status)) + ", residual " +
                     format_number(r.residual) + ")";
  }
  warn(t, contact, stats_.message);
  return true;
}

// The work of the stage's last impulses, booked as book_impulses does: per contact of the
// index set, the normal impulse along W_N and (with tangential unknowns) the tangential one.
void EventDriven::book_stage_impulses(const std::vector<int>& index, const Vector& u_minus,
                                      const Vector& u_plus) {
  for (std::size_t j = 0; j < index.size(); ++j) {
    const auto& c = cbuf_[idx(index[j])];
    const int jj = static_cast<int>(j);
    const double ln = stage_.lambda_n(jj), lt = stage_.lambda_t(jj);
    const double mid_n = 0.5 * (c.w_normal.dot(u_minus) + c.w_normal.dot(u_plus));
    impact_normal_work_ += ln * (mid_n + c.what_normal);
    impact_ground_work_ -= ln * c.what_normal;
    if (stage_.kinematics().tangential()) {
      const double mid_t = 0.5 * (c.w_tangent.dot(u_minus) + c.w_tangent.dot(u_plus));
      impact_friction_work_ += lt * (mid_t + c.what_tangent);
      impact_ground_work_ -= lt * c.what_tangent;
    }
  }
}

void EventDriven::project_positions(double t, Vector& q, const Vector& u) {
  // Closest point in the kinetic metric on g_N,i(q) = 0 for every closed contact:
  //   dq = -M^-1 W (W^T M^-1 W)^+ g      (Newton iterations on the gap functions).
  std::vector<int> closed_set;
  for (int i = 0; i < m_; ++i) {
    if (closed(modes_[idx(i)])) closed_set.push_back(i);
  }
  if (closed_set.empty()) return;
  const int k = static_cast<int>(closed_set.size());
  Matrix W(n_, k);
  Vector g(k);
  for (int it = 0; it < kProjectionIterations; ++it) {
    sys_.contact_data(t, q, u, cbuf_);
    for (int j = 0; j < k; ++j) {
      W.col(j) = cbuf_[idx(closed_set[idx(j)])].w_normal;
      g[j] = cbuf_[idx(closed_set[idx(j)])].gap_normal;
    }
    if (g.cwiseAbs().maxCoeff() <= 1e-15) break;
    const Matrix G = W.transpose() * minv_ * W;
    q -= minv_ * (W * G.completeOrthogonalDecomposition().solve(g));
  }
}

void EventDriven::project_velocities(double t, const Vector& q, Vector& u) {
  // gdot_N = 0 for closed contacts and gdot_T = 0 for sticking ones, closest in the kinetic
  // metric: du = -M^-1 R (R^T M^-1 R)^+ (R^T u + what), the effect of the impulses
  // P = -(R^T M^-1 R)^+ (R^T u + what) along R. Their work is booked like an impact's.
  sys_.contact_data(t, q, u, cbuf_);
  int k = 0;
  for (const auto& md : modes_) {
    if (closed(md)) ++k;
    if (md == ContactState::kStick) ++k;
  }
  if (k == 0) return;
  Matrix R(n_, k);
  Vector r(k), what(k);
  std::vector<bool> tangential(static_cast<std::size_t>(k), false);
  int j = 0;
  for (int i = 0; i < m_; ++i) {
    const auto& c = cbuf_[idx(i)];
    const auto& md = modes_[idx(i)];
    if (!closed(md)) continue;
    R.col(j) = c.w_normal;
    what[j] = c.what_normal;
    r[j++] = c.gap_rate(u);
    if (md == ContactState::kStick) {
      R.col(j) = c.w_tangent;
      what[j] = c.what_tangent;
      tangential[idx(j)] = true;
      r[j++] = c.slip_rate(u);
    }
  }
  const Matrix G = R.transpose() * minv_ * R;
  const Vector impulse = -G.completeOrthogonalDecomposition().solve(r);
  const Vector u_plus = u + minv_ * (R * impulse);
  book_impulses(R, impulse, what, tangential, u, u_plus);
  u = u_plus;
}

// Work of impulses P along the columns of W for a velocity jump u- -> u+:
// P . W^T (u- + u+)/2 (Glocker 2001), split as for the contact forces into the work in the
// contact, P . gdot_mid (normal: impacts, tangential: friction), and the work of the moving
// seats, -P . what (ground).
void EventDriven::book_impulses(const Matrix& W, const Vector& impulse, const Vector& what,
                                const std::vector<bool>& tangential, const Vector& u_minus,
                                const Vector& u_plus) {
  const Vector u_mid = 0.5 * (u_minus + u_plus);
  for (Eigen::Index j = 0; j < impulse.size(); ++j) {
    const double in_contact = impulse[j] * (W.col(j).dot(u_mid) + what[j]);
    (tangential[static_cast<std::size_t>(j)] ? impact_friction_work_ : impact_normal_work_) +=
        in_contact;
    impact_ground_work_ -= impulse[j] * what[j];
  }
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
  stats_.energy = e;
  return e.error;
}

void EventDriven::record_sample(double t, const State& x, bool force) {
  indicators(t, x);  // fills contact data and the phase's contact forces at (t, x)
  const double err = balance_error(t, x);
  if (force) {
    rec_.sample_now(t, q_, u_, cbuf_, lambda_n_, lambda_t_, err);
  } else {
    rec_.sample(t, q_, u_, cbuf_, lambda_n_, lambda_t_, err);
  }
}

// Zeno guard: a bounded number of events per window of time. Sets `forced` while touching
// contacts are forced closed; returns false when the bound is reached again under forced
// closure (the run stalls).
bool EventDriven::zeno_guard(double t, int trigger_contact, bool initial, bool& forced) {
  forced = t < forced_closure_until_;
  if (initial) return true;
  recent_events_.push_back(t);
  while (!recent_events_.empty() && recent_events_.front() < t - opt_.event_window) {
    recent_events_.pop_front();
  }
  const auto count = static_cast<int>(recent_events_.size());
  if (count >= 2 * opt_.max_events_per_window) {
    warn(t, trigger_contact, "event bound reached again under forced closure; run stopped");
    stats_.message = "more than " + std::to_string(2 * opt_.max_events_per_window) +
                     " events within " + format_number(opt_.event_window) + " s at t = " +
                     format_number(t) + " s";
    stalled_ = true;
    return false;
  }
  if (count >= opt_.max_events_per_window && !forced) {
    warn(t, trigger_contact,
         "event bound reached (" + std::to_string(count) + " events within " +
             format_number(opt_.event_window) + " s): touching contacts forced closed");
    forced_closure_until_ = t + opt_.event_window;
    forced = true;
  }
  return true;
}

// Step 1, location's outcome: the contacts touching at t (closed, or open within
// gap_tolerance) and whether one of them is closing faster than the Zeno threshold.
void EventDriven::find_touching(double t, const Vector& q, const Vector& u, bool initial,
                                bool& any_impact) {
  sys_.forces(t, q, u, f_);
  sys_.contact_data(t, q, u, cbuf_);
  touching_.clear();
  any_impact = false;
  for (int i = 0; i < m_; ++i) {
    const auto& c = cbuf_[idx(i)];
    const bool is_touching = closed(modes_[idx(i)]) || c.gap_normal <= gap_tolerance_;
    if (!is_touching) continue;
    touching_.push_back(i);
    if (c.gap_rate(u) < -closing_velocity_) any_impact = true;
    if (initial && c.gap_normal < -gap_tolerance_) {
      warn(t, i + 1, "initial penetration g_N = " + format_number(c.gap_normal) + " m");
    }
  }
}

// Step 2, the impact problem: eq. (6) on every touching contact that is closing or resting,
// with the pre-impact velocities and Newton's law (restitution 0 under forced closure).
// Touching contacts that separate are left out: an impulse elsewhere that would make them
// close is caught as an impact just after. Returns false when the run must stop.
bool EventDriven::impact_problem(double t, Vector& u, bool forced, int trigger_contact) {
  touching_.erase(std::remove_if(touching_.begin(), touching_.end(),
                                 [&](int i) {
                                   return cbuf_[idx(i)].gap_rate(u) > closing_velocity_;
                                 }),
                  touching_.end());
  bool frictionless = true;
  for (int i : touching_) frictionless = frictionless && cbuf_[idx(i)].friction == 0.0;
  lcp::FrictionalProblem& fp =
      stage_.build(cbuf_, touching_, !frictionless, minv_, u, ContactLevel::kVelocity);
  for (std::size_t j = 0; j < touching_.size(); ++j) {
    const auto& c = cbuf_[idx(touching_[j])];
    const auto jj = static_cast<Eigen::Index>(j);
    fp.gdot_n_minus[jj] = std::min(0.0, c.gap_rate(u));
    if (forced) fp.restitution[jj] = 0.0;
  }
  const ContactStatus status = stage_.solve();
  if (stage_failed(t, trigger_contact, status, "impact problem (eq. 6)")) return false;
  u_plus_ = u;
  stage_.apply(u_plus_);
  book_stage_impulses(touching_, u, u_plus_);
  for (int i : touching_) {
    if (cbuf_[idx(i)].gap_rate(u) < -closing_velocity_) rec_.event(t, i + 1, EventKind::kImpact);
  }
  u = u_plus_;
  return true;
}

// Step 3a: candidates for closure are the touching contacts not separating faster than
// closing_velocity; each is a stick candidate when frictional and slower than stick_velocity,
// else sliding in the direction of its slip velocity.
void EventDriven::closure_candidates(const Vector& u) {
  // A slip event is located where s gdot_T + velocity_shift_ turns negative, so the slip
  // velocity there is velocity_shift_ (plus the Brent bracket's overshoot, far smaller):
  // a stick threshold below it (stick_velocity = 10 tolerance is 1e-10 m/s at tolerance
  // 1e-11, the shift 3e-10 m/s at 2 m/s) would take the contact for sliding the other way
  // and fire the reversal again at once. Twice the shift covers the overshoot.
  const double stick = std::max(stick_velocity_, 2.0 * velocity_shift_);
  for (auto& md : modes_) md = ContactState::kOpen;
  for (int i : touching_) {
    const auto& c = cbuf_[idx(i)];
    if (c.gap_rate(u) > closing_velocity_) continue;
    if (c.friction > 0.0 && std::abs(c.slip_rate(u)) <= stick) {
      modes_[idx(i)] = ContactState::kStick;
    } else {
      const double sgn = c.friction > 0.0 ? (c.slip_rate(u) > 0.0 ? 1.0 : -1.0) : 0.0;
      modes_[idx(i)] = slip_state(sgn);
    }
  }
}

// Step 3b, the contact problem: eq. (6) at acceleration level on the candidates, eps = 0
// (Pfeiffer & Glocker 1996, ch. 6). Sliding contacts carry lambda_T = -mu s lambda_N in their
// normal column and no tangential unknown. Sets the modes of the next phase. Returns false
// when the run must stop.
bool EventDriven::contact_problem(double t, Vector& q, Vector& u) {
  candidates_.clear();
  for (int i = 0; i < m_; ++i) {
    if (closed(modes_[idx(i)])) candidates_.push_back(i);
  }
  if (candidates_.empty()) return true;
  sys_.forces(t, q, u, f_);
  sys_.contact_data(t, q, u, cbuf_);
  bool tangential = false;
  for (std::size_t j = 0; j < candidates_.size(); ++j) {
    const auto& c = cbuf_[idx(candidates_[j])];
    const auto& md = modes_[idx(candidates_[j])];
    tangential = tangential || md == ContactState::kStick;
    slip_coupling_[j] = -c.friction * slip_sign(md);
  }
  a_free_.noalias() = minv_ * f_;
  lcp::FrictionalProblem& fp = stage_.build(cbuf_, candidates_, tangential, minv_, a_free_,
                                            ContactLevel::kAcceleration, slip_coupling_.data());
  for (std::size_t j = 0; j < candidates_.size(); ++j) {
    const auto& md = modes_[idx(candidates_[j])];
    if (tangential && md == ContactState::kStick) {
      fp.friction[static_cast<Eigen::Index>(j)] = cbuf_[idx(candidates_[j])].friction;
    }
  }
  const ContactStatus status = stage_.solve();
  if (status == ContactStatus::kUnsolved) {
    // The candidates keep their modes, and the run goes on; the status says
    // contact_unsolved from here (failure_time: the first such event).
    if (std::isnan(first_unsolved_)) first_unsolved_ = t;
    warn(t, candidates_.front() + 1,
         "contact problem (eq. 6, accelerations) not solved by any solver of the chain "
         "(residual " + format_number(stage_.result().residual) +
             "): touching contacts kept closed in their current modes");
    return true;
  }
  if (stage_failed(t, candidates_.front() + 1, status, "contact problem (eq. 6, accelerations)")) {
    return false;
  }
  const lcp::FrictionalResult& r = stage_.result();
  // Scale of the accelerations, for "gddot = 0" decisions on round-off.
  const double acc_scale = 1e-9 * (1.0 + fp.gdot_free.cwiseAbs().maxCoeff());
  const double force_scale = 1.0 + f_.cwiseAbs().maxCoeff();
  for (std::size_t j = 0; j < candidates_.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    auto& md = modes_[idx(candidates_[j])];
    // Closed only under a positive normal force: at a lift-off both lambda_N and gddot_N
    // pass through 0, and keeping a contact closed on gddot_N = 0 would fire the lift-off
    // again at once.
    if (!(r.lambda_n[jj] > kClosedForce * force_scale)) {
      md = ContactState::kOpen;
      continue;
    }
    if (md != ContactState::kStick) continue;
    // Stick while the friction force is inside the cone; on its boundary the contact slips
    // against the friction force, lambda_T = -mu s lambda_N (eq. 5). Deciding on the force
    // rather than on the sign of gddot_T, which is round-off at a stick-slip transition,
    // keeps a transition from firing again at once.
    const double lt = r.lambda_t[jj], cone = fp.friction[jj] * r.lambda_n[jj];
    const bool saturated = std::abs(lt) >= cone * (1.0 - kConeSaturation) && cone > 0.0;
    const double at = r.gdot_t_plus[jj];
    if (saturated || std::abs(at) > acc_scale) {
      const double sgn = saturated && lt != 0.0 ? (lt > 0.0 ? -1.0 : 1.0) : (at > 0.0 ? 1.0 : -1.0);
      md = slip_state(sgn);
    }
  }
  return true;
}

// Step 5: events for the mode changes.
void EventDriven::record_mode_changes(double t, const std::vector<ContactState>& old) {
  for (int i = 0; i < m_; ++i) {
    const auto& a = old[idx(i)];
    const auto& b = modes_[idx(i)];
    if (!closed(a) && closed(b)) rec_.event(t, i + 1, EventKind::kClose);
    if (closed(a) && !closed(b)) rec_.event(t, i + 1, EventKind::kOpen);
    if (b == ContactState::kStick && a != ContactState::kStick) rec_.event(t, i + 1, EventKind::kStick);
    if (sliding(b) && a != b) {
      rec_.event(t, i + 1, EventKind::kSlip);
    }
  }
}

// Resolves what happens at time t in state x (modified in place), along the steps of
// Shi & Dimitrakopoulos (2017), section 2.2: the located event's touching contacts, the
// impact problem, the contact problem that sets the modes of the next phase, the projection
// onto the constraints, and the mode update. Returns false if the run must stop.
bool EventDriven::handle_event(double t, State& x, int trigger_contact, bool initial) {
  unpack(x, q_event_, u_event_);
  Vector& q = q_event_;
  Vector& u = u_event_;
  if (!q.allFinite() || !u.allFinite()) {
    diverged_ = true;
    stats_.message = "non-finite state at t = " + format_number(t) + " s";
    warn(t, trigger_contact, stats_.message);
    return false;
  }
  bool forced = false;
  if (!zeno_guard(t, trigger_contact, initial, forced)) return false;

  bool any_impact = false;
  find_touching(t, q, u, initial, any_impact);
  bool solved_lcp = false;
  if (any_impact) {
    solved_lcp = true;
    if (!impact_problem(t, u, forced, trigger_contact)) return false;
  }

  old_modes_ = modes_;
  closure_candidates(u);
  // Project the candidates onto the constraint manifold (drift correction, and gdot_N = 0
  // for a contact whose post-impact velocity is below the Zeno threshold).
  project_positions(t, q, u);
  project_velocities(t, q, u);
  bool any_candidate = false;
  for (const auto& md : modes_) any_candidate = any_candidate || closed(md);
  if (any_candidate) {
    solved_lcp = true;
    if (!contact_problem(t, q, u)) return false;
    // Final projection with the decided modes (sticking contacts get gdot_T = 0).
    project_positions(t, q, u);
    project_velocities(t, q, u);
  }
  if (solved_lcp) ++stats_.steps_with_lcp;
  record_mode_changes(t, old_modes_);

  // Indicator shifts for the new phase, scaled to the forces and velocities in play.
  sys_.forces(t, q, u, f_);
  force_shift_ = kIndicatorShift * (1.0 + f_.cwiseAbs().maxCoeff());
  velocity_shift_ = kIndicatorShift * (1.0 + u.cwiseAbs().maxCoeff());

  for (int i = 0; i < n_; ++i) {
    x[idx(i)] = q[i];
    x[idx(n_ + i)] = u[i];
  }
  return true;
}

void EventDriven::finish_counts() {
  const ContactStageCounts& counts = stage_.counts();
  stats_.lcp_solves = counts.solves;
  stats_.lcp_fallbacks = counts.fallbacks;
  stats_.lcp_unsolved = counts.unsolved;
  constexpr int kStatuses = static_cast<int>(lcp::Status::kTooLarge) + 1;
  for (int s = 0; s < kStatuses; ++s) {
    if (counts.by_status[s] > 0) {
      stats_.lcp_status[std::string(lcp::to_string(static_cast<lcp::Status>(s)))] =
          counts.by_status[s];
    }
  }
}

RunResult EventDriven::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  gsl_error_handler_t* old_handler = gsl_set_error_handler_off();
  double t = sys_.initial_time();
  const double t_end = opt_.end_time;
  if (!(t_end > t)) {
    gsl_set_error_handler(old_handler);
    throw std::invalid_argument("event_driven options: end_time must be > the initial time " +
                                format_number(t) + " s");
  }
  State x(static_cast<std::size_t>(2 * n_ + kEnergyTerms), 0.0);
  {
    const Vector q0 = sys_.initial_position(), u0 = sys_.initial_velocity();
    if (q0.size() != n_ || u0.size() != n_) {
      gsl_set_error_handler(old_handler);
      throw std::invalid_argument("event_driven: initial state has the wrong size");
    }
    for (int i = 0; i < n_; ++i) {
      x[idx(i)] = q0[i];
      x[idx(n_ + i)] = u0[i];
    }
    initial_energy_ = 0.5 * u0.dot(sys_.mass() * u0) + sys_.energy(t, q0).stored;
  }
  const double sample_dt = rec_.sample_dt();
  const double max_step = opt_.max_step;
  dense_ = odeint::make_dense_output(opt_.tolerance, opt_.tolerance, max_step, Dopri());

  auto finish = [&](bool completed) {
    stats_.completed = completed;
    stats_.end_time = t;
    // A non-finite state is not recorded (nor handed to the system): the history ends with
    // the last finite sample.
    if (std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) {
      record_sample(t, x, true);
    } else {
      diverged_ = true;
    }
    if (progress_) progress_(t);
    finish_counts();
    if (!std::isfinite(stats_.energy.error)) diverged_ = true;
    finish_status(stats_, diverged_, stalled_ || (!completed && !diverged_ && stats_.lcp_unsolved == 0));
    if (!succeeded(stats_.status)) {
      stats_.failure_time =
          stats_.status == RunStatus::kContactUnsolved && !std::isnan(first_unsolved_)
              ? first_unsolved_
              : t;
    }
    stats_.wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    gsl_set_error_handler(old_handler);
    return stats_;
  };

  if (!handle_event(t, x, 0, true)) return finish(false);
  sys_.commit();
  record_sample(t, x, false);
  next_sample_ = sample_dt > 0.0 ? t + sample_dt : t;

  auto rhs_fn = [this](const State& xx, State& dxdt, double tt) { rhs(xx, dxdt, tt); };
  double dt = std::min(opt_.initial_step, t_end - t);
  dense_.initialize(x, t, dt);
  indicators(t, x);
  Vector h_prev = h_;
  const double min_step = 1e-14;

  while (t < t_end) {
    const std::int64_t evals0 = rhs_evaluations_;
    dense_.do_step(std::ref(rhs_fn));
    const std::int64_t evals = rhs_evaluations_ - evals0;
    // Dormand–Prince with FSAL costs six right-hand sides per attempt, plus one for the
    // derivative at the start of a phase (after initialize()).
    stats_.rejected_steps += std::max<std::int64_t>(0, evals / 6 - 1);
    ++stats_.steps;
    const double ta = dense_.previous_time();
    double tb = std::min(dense_.current_time(), t_end);
    if (!(dense_.current_time_step() > min_step * std::max(1.0, std::abs(ta)))) {
      stats_.message = "step size underflow at t = " + format_number(ta) + " s";
      warn(ta, 0, stats_.message);
      stalled_ = true;
      t = ta;
      dense_.calc_state(ta, x);
      return finish(false);
    }
    dense_.calc_state(tb, x);
    if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) {
      // The step went non-finite (a force blew up): stop at its start, the last finite state.
      diverged_ = true;
      stats_.message = "non-finite state in the step from t = " + format_number(ta) + " s";
      warn(ta, 0, stats_.message);
      t = ta;
      dense_.calc_state(ta, x);
      return finish(false);
    }
    if (progress_ && stats_.steps % kProgressInterval == 0) progress_(tb);
    indicators(tb, x);
    Vector h_b = h_;
    // Earliest event in (ta, tb].
    double t_event = std::numeric_limits<double>::infinity();
    int k_event = -1;
    for (int k = 0; k < 2 * m_; ++k) {
      const double te = locate(k, ta, tb, h_prev[k], h_b[k]);
      if (te < t_event) {
        t_event = te;
        k_event = k;
      }
    }
    const double t_stop = std::min(t_event, tb);
    // Samples from the dense output up to the end of this piece.
    if (sample_dt > 0.0) {
      while (next_sample_ <= t_stop) {
        dense_.calc_state(next_sample_, xs_);
        State xsample = xs_;
        record_sample(next_sample_, xsample, false);
        next_sample_ += sample_dt;
      }
    }
    t = t_stop;
    dense_.calc_state(t, x);
    if (sample_dt == 0.0) record_sample(t, x, false);
    if (k_event >= 0 && t_event <= tb) {
      if (!handle_event(t, x, k_event / 2 + 1, false)) {
        sys_.commit();
        return finish(false);
      }
      sys_.commit();
      dt = std::max(dense_.current_time_step(), 1e3 * min_step * std::max(1.0, std::abs(t)));
      dt = std::min(dt, std::max(t_end - t, min_step));
      if (t >= t_end) break;
      dense_.initialize(x, t, dt);
      indicators(t, x);
      h_prev = h_;
      continue;
    }
    // No event: commit the step's internal state; correct drift of closed contacts if it
    // exceeds the gap tolerance.
    unpack(x, q_, u_);
    sys_.forces(t, q_, u_, f_);
    sys_.commit();
    h_prev = h_b;
    if (t >= t_end) break;
    bool drift = false;
    sys_.contact_data(t, q_, u_, cbuf_);
    for (int i = 0; i < m_; ++i) {
      if (!closed(modes_[idx(i)])) continue;
      const auto& c = cbuf_[idx(i)];
      drift = drift || std::abs(c.gap_normal) > gap_tolerance_ ||
              std::abs(c.gap_rate(u_)) > closing_velocity_;
    }
    if (drift) {
      Vector q = q_, u = u_;
      project_positions(t, q, u);
      project_velocities(t, q, u);
      for (int i = 0; i < n_; ++i) {
        x[idx(i)] = q[i];
        x[idx(n_ + i)] = u[i];
      }
      dense_.initialize(x, t, dense_.current_time_step());
      indicators(t, x);
      h_prev = h_;
    }
  }
  t = std::min(t, t_end);
  return finish(true);
}

}  // namespace

RunResult event_driven(System& system, const EventDrivenOptions& options, Recorder& recorder,
                       const Progress& progress) {
  options.validate();
  EventDriven integrator(system, options, recorder, progress);
  return integrator.run();
}

}  // namespace nsb::integrators
