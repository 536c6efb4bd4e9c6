#include "integrators/moreau_jean.hpp"

#include "lcp/frictional.hpp"

#include <Eigen/LU>

#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace nsb::integrators {

namespace {

// Relative slack when comparing times, so that round-off in end_time / h neither adds a
// spurious sliver of a step nor drops the last one.
constexpr double kTimeSlack = 1e-9;
// Largest number of steps a run may take: beyond it the step is certainly a unit mistake.
constexpr double kMaxSteps = 1e10;
// Unsolved contact problems reported one by one (events and RunResult::warnings); more are
// only counted, so a persistently failing solver cannot flood the outputs.
constexpr std::int64_t kMaxWarnings = 100;
// Number of lcp::Status values (kNotRun .. kTooLarge), for allocation-free counting.
constexpr int kStatusCount = static_cast<int>(lcp::Status::kTooLarge) + 1;

// y += alpha A x. The systems here are tiny (3 DOF for the bridge), where the general
// matrix-vector kernel's dispatch costs more than the arithmetic. Per row the products are
// summed over the columns in order, then scaled by alpha and added, as Eigen's column-major
// kernel does (the bridge benchmark's histories came out bit for bit the same).
void add_product(double alpha, const Matrix& a, const Vector& x, Vector& y) {
  const Eigen::Index rows = a.rows(), cols = a.cols();
  for (Eigen::Index i = 0; i < rows; ++i) {
    double c = 0.0;
    for (Eigen::Index j = 0; j < cols; ++j) c += a(i, j) * x[j];
    y[i] += c * alpha;
  }
}

// Per-contact state, for events (impact, close, open, stick, slip).
enum class ContactState { kOpen, kClosed /* frictionless */, kStick, kSlipPositive, kSlipNegative };

class MoreauJean {
 public:
  MoreauJean(System& system, const MoreauJeanOptions& options, Recorder& recorder);
  RunResult run();

 private:
  void factorize(double h);
  bool step(double h, double t1);  // false when the step failed (non-finite state)
  void solve_contacts(double h);
  void update_events(double t1);
  void accumulate_smooth_work(double h);
  double energy_error();
  void sample(bool force);

  System& system_;
  const MoreauJeanOptions& options_;
  Recorder& recorder_;
  const Matrix& mass_;
  int n_ = 0;  // degrees of freedom
  int m_ = 0;  // potential contacts
  double theta_ = 0.5;

  // State at t_k, and the end-of-step values being computed.
  double t_ = 0.0;
  Vector q_, u_, q_new_, u_new_, u_free_, rhs_, f_k_, f_pred_, mu_tmp_;

  // Tangent of the committed state and the iteration matrix A = M + h theta C + h^2 theta^2 K.
  Matrix K_, C_, A_, A_inv_, identity_;
  Eigen::PartialPivLU<Matrix> lu_;
  double h_factored_ = -1.0;
  bool refactor_ = true;
  bool has_stiffness_ = false;

  // Contacts: data at t_k, the active index set, its columns [W_N | W_T] and A^-1 of them.
  std::vector<ContactData> contacts_;
  std::vector<int> active_;
  bool active_friction_ = false;
  Matrix w_active_, a_inv_w_;
  Vector impulse_active_;  // [Lambda_N; Lambda_T] of the active contacts
  // One preallocated problem per index-set size k = 1..m, frictional (2k) and not (k).
  std::vector<lcp::FrictionalProblem> frictional_, frictionless_;
  lcp::SolveOptions solve_options_;
  lcp::FrictionalSolver solver_;
  std::vector<lcp::FrictionalResult> frictional_result_, frictionless_result_;
  Vector lambda_n_, lambda_t_;  // impulses of every contact in this step [kN s]
  Vector force_n_, force_t_;    // lambda = Lambda / h, for the history [kN]
  std::vector<ContactState> state_;
  std::vector<char> in_index_set_;  // per contact: in the index set of this step

  // Energy bookkeeping: works accumulated since t0, and the powers at t_k.
  EnergyBalance energy_;
  PowerTerms power_k_;

  RunResult stats_;
  std::array<std::int64_t, kStatusCount> status_count_{};
  std::int64_t unsolved_ = 0;  // contact problems that ended without kSolved
  double last_sample_t_ = -1e300;
};

MoreauJean::MoreauJean(System& system, const MoreauJeanOptions& options, Recorder& recorder)
    : system_(system),
      options_(options),
      recorder_(recorder),
      mass_(system.mass()),
      n_(system.dofs()),
      m_(system.contacts()),
      theta_(options.theta) {
  options.validate();
  checked_inverse_mass(system, "moreau_jean");
  t_ = system.initial_time();
  q_ = system.initial_position();
  u_ = system.initial_velocity();
  if (!(options.end_time > t_)) {
    throw std::invalid_argument("moreau_jean: end_time (" + std::to_string(options.end_time) +
                                ") must exceed the system's initial time (" +
                                std::to_string(t_) + ")");
  }
  if ((options.end_time - t_) / options.step > kMaxSteps) {
    throw std::invalid_argument("moreau_jean: step is too small for end_time (more than 1e10 "
                                "steps)");
  }
  q_new_ = Vector::Zero(n_);
  u_new_ = Vector::Zero(n_);
  u_free_ = Vector::Zero(n_);
  rhs_ = Vector::Zero(n_);
  f_k_ = Vector::Zero(n_);
  f_pred_ = Vector::Zero(n_);
  mu_tmp_ = Vector::Zero(n_);
  K_ = Matrix::Zero(n_, n_);
  C_ = Matrix::Zero(n_, n_);
  A_ = Matrix::Zero(n_, n_);
  A_inv_ = Matrix::Zero(n_, n_);
  identity_ = Matrix::Identity(n_, n_);
  lu_ = Eigen::PartialPivLU<Matrix>(n_);

  contacts_ = system.make_contact_buffer();
  active_.reserve(static_cast<std::size_t>(m_));
  w_active_ = Matrix::Zero(n_, 2 * m_);
  a_inv_w_ = Matrix::Zero(n_, 2 * m_);
  impulse_active_ = Vector::Zero(2 * m_);
  frictional_.resize(static_cast<std::size_t>(m_) + 1);
  frictionless_.resize(static_cast<std::size_t>(m_) + 1);
  for (int k = 1; k <= m_; ++k) {
    for (auto* p : {&frictional_[static_cast<std::size_t>(k)],
                    &frictionless_[static_cast<std::size_t>(k)]}) {
      const int size = (p == &frictional_[static_cast<std::size_t>(k)]) ? 2 * k : k;
      p->delassus = Matrix::Zero(size, size);
      p->gdot_free = Vector::Zero(size);
      p->gdot_n_minus = Vector::Zero(k);
      p->restitution = Vector::Zero(k);
      p->friction = Vector::Zero(k);
    }
  }
  solve_options_.tolerance = options.lcp_tolerance;
  solver_.reserve(m_);
  frictional_result_.resize(static_cast<std::size_t>(m_) + 1);
  frictionless_result_.resize(static_cast<std::size_t>(m_) + 1);
  lambda_n_ = Vector::Zero(m_);
  lambda_t_ = Vector::Zero(m_);
  force_n_ = Vector::Zero(m_);
  force_t_ = Vector::Zero(m_);
  state_.assign(static_cast<std::size_t>(m_), ContactState::kOpen);
  in_index_set_.assign(static_cast<std::size_t>(m_), 0);

  // The initial state is accepted as it is: evaluate and commit it, so that f_k, K and C
  // belong to the committed state at t0.
  system_.forces(t_, q_, u_, f_k_);
  system_.tangent(t_, q_, u_, K_, C_);
  system_.commit();
  system_.contact_data(t_, q_, u_, contacts_);
  if (static_cast<int>(contacts_.size()) != m_) {
    throw std::invalid_argument("moreau_jean: contact_data() did not fill contacts() entries");
  }
  power_k_ = system_.power(t_, q_, u_);
  const EnergyState e0 = system_.energy(t_, q_);
  mu_tmp_.noalias() = mass_ * u_;
  energy_.initial = 0.5 * u_.dot(mu_tmp_) + e0.stored;
  stats_.method = "moreau";
}

// A = M + h theta C + h^2 theta^2 K (Acary & Brogliato 2008, ch. 10), and its inverse,
// kept explicitly: the systems are small, and A^-1 W then costs one product per step.
void MoreauJean::factorize(double h) {
  const double ht = h * theta_;
  A_ = mass_;
  A_ += ht * C_;
  A_ += (ht * ht) * K_;
  lu_.compute(A_);
  A_inv_ = lu_.solve(identity_);
  has_stiffness_ = !K_.isZero(0.0);
  h_factored_ = h;
  refactor_ = false;
  ++stats_.factorizations;
}

RunResult MoreauJean::run() {
  const auto start = std::chrono::steady_clock::now();
  const double t0 = t_;
  const double h = options_.step;
  const double duration = options_.end_time - t0;
  const auto steps = static_cast<std::int64_t>(std::ceil(duration / h - kTimeSlack));

  sample(true);
  stats_.completed = true;
  for (std::int64_t k = 0; k < steps; ++k) {
    const bool last = (k + 1 == steps);
    const double t1 = last ? options_.end_time : t0 + static_cast<double>(k + 1) * h;
    // Keep the nominal h (and its factorization) unless the last step is really shorter.
    const double hk = (last && std::abs((t1 - t_) - h) > kTimeSlack * h) ? t1 - t_ : h;
    if (!step(hk, t1)) {
      stats_.completed = false;
      break;
    }
    sample(last);
    if (options_.progress && (stats_.steps % options_.progress_interval == 0)) {
      options_.progress(t_);
    }
  }
  if (options_.progress) options_.progress(t_);
  if (stats_.completed) {
    stats_.message = "reached end_time";
  } else if (last_sample_t_ != t_) {
    sample(true);
  }

  // The final energy balance.
  mu_tmp_.noalias() = mass_ * u_;
  const EnergyState e = system_.energy(t_, q_);
  energy_.kinetic = 0.5 * u_.dot(mu_tmp_);
  energy_.stored = e.stored;
  energy_.hysteretic = e.hysteretic;
  energy_.close();
  stats_.energy = energy_;
  stats_.end_time = t_;
  for (int s = 0; s < kStatusCount; ++s) {
    if (status_count_[static_cast<std::size_t>(s)] > 0) {
      stats_.lcp_status[std::string(lcp::to_string(static_cast<lcp::Status>(s)))] =
          status_count_[static_cast<std::size_t>(s)];
    }
  }
  stats_.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats_;
}

bool MoreauJean::step(double h, double t1) {
  if (refactor_ || h != h_factored_) factorize(h);

  // Free velocity: the theta-method with the smooth force linearised about (q_k, u_k),
  //   A (u_free - u_k) = h [(1-theta) f_k + theta f(t_k+1, q_k, u_k)] - h^2 theta K u_k.
  system_.forces(t1, q_, u_, f_pred_);
  rhs_ = (h * (1.0 - theta_)) * f_k_;
  rhs_ += (h * theta_) * f_pred_;
  if (has_stiffness_) add_product(-(h * h * theta_), K_, u_, rhs_);
  u_free_ = u_;
  add_product(1.0, A_inv_, rhs_, u_free_);

  // Index set: contacts closed or closing within the step, g_N + (h/2) gdot_N <= 0, with
  // g_N and gdot_N at t_k (Acary & Brogliato 2008, ch. 10; Siconos uses the same rule).
  active_.clear();
  active_friction_ = false;
  for (int i = 0; i < m_; ++i) {
    const ContactData& c = contacts_[static_cast<std::size_t>(i)];
    in_index_set_[static_cast<std::size_t>(i)] = 0;
    if (c.far) continue;
    if (c.gap_normal + 0.5 * h * c.gap_rate(u_) <= 0.0) {
      in_index_set_[static_cast<std::size_t>(i)] = 1;
      active_.push_back(i);
      if (c.friction > 0.0) active_friction_ = true;
    }
  }
  u_new_ = u_free_;
  lambda_n_.setZero();
  lambda_t_.setZero();
  if (!active_.empty()) solve_contacts(h);

  q_new_ = q_;
  q_new_ += (h * (1.0 - theta_)) * u_;
  q_new_ += (h * theta_) * u_new_;
  if (!q_new_.allFinite() || !u_new_.allFinite()) {
    system_.revert();
    stats_.message = "non-finite state at t = " + std::to_string(t1) +
                     " (the step or the model's forces are unstable)";
    recorder_.event(t1, 0, EventKind::kWarning, stats_.message);
    stats_.warnings.push_back(stats_.message);
    return false;
  }

  // Work of the contact impulses on the system over the step: Lambda . W^T (u_k + u_k+1)/2,
  // the exact change of kinetic energy they cause (Acary & Brogliato 2008, ch. 10).
  for (int i : active_) {
    const ContactData& c = contacts_[static_cast<std::size_t>(i)];
    const double ln = lambda_n_[i];
    const double lt = lambda_t_[i];
    if (ln != 0.0) energy_.impacts += ln * 0.5 * (c.w_normal.dot(u_) + c.w_normal.dot(u_new_));
    if (lt != 0.0) energy_.friction += lt * 0.5 * (c.w_tangent.dot(u_) + c.w_tangent.dot(u_new_));
  }
  update_events(t1);

  // Accept the step: evaluate the end state, keep its tangent if it changed, commit once.
  system_.forces(t1, q_new_, u_new_, f_k_);
  if (system_.tangent_changed()) {
    system_.tangent(t1, q_new_, u_new_, K_, C_);
    refactor_ = true;
  }
  system_.commit();
  std::swap(q_, q_new_);
  std::swap(u_, u_new_);
  t_ = t1;
  ++stats_.steps;
  system_.contact_data(t_, q_, u_, contacts_);
  accumulate_smooth_work(h);
  for (int i = 0; i < m_; ++i) {
    force_n_[i] = lambda_n_[i] / h;
    force_t_[i] = lambda_t_[i] / h;
  }
  return true;
}

void MoreauJean::solve_contacts(double h) {
  ++stats_.steps_with_lcp;
  const int k = static_cast<int>(active_.size());
  const int size = active_friction_ ? 2 * k : k;
  for (int j = 0; j < k; ++j) {
    const ContactData& c = contacts_[static_cast<std::size_t>(active_[static_cast<std::size_t>(j)])];
    w_active_.col(j) = c.w_normal;
    if (active_friction_) w_active_.col(k + j) = c.w_tangent;
  }
  auto w = w_active_.leftCols(size);
  auto a_inv_w = a_inv_w_.leftCols(size);
  a_inv_w.noalias() = A_inv_ * w;

  lcp::FrictionalProblem& p = active_friction_ ? frictional_[static_cast<std::size_t>(k)]
                                               : frictionless_[static_cast<std::size_t>(k)];
  // Delassus matrix G = W^T A^-1 W, normals first (lcp/frictional.hpp, eq. 8 with A for M).
  p.delassus.noalias() = w.transpose() * a_inv_w;
  for (int j = 0; j < k; ++j) {
    const ContactData& c = contacts_[static_cast<std::size_t>(active_[static_cast<std::size_t>(j)])];
    p.gdot_free[j] = c.w_normal.dot(u_free_) + c.what_normal;
    p.gdot_n_minus[j] = c.gap_rate(u_);
    p.restitution[j] = c.restitution;
    p.friction[j] = c.friction;
    if (active_friction_) p.gdot_free[k + j] = c.w_tangent.dot(u_free_) + c.what_tangent;
  }

  ++stats_.lcp_solves;
  auto impulse = impulse_active_.head(size);
  const double g11 = p.delassus(0, 0);
  if (size == 1 && g11 > 0.0) {
    // One frictionless contact: the 1 x 1 LCP  g11 Lambda + b >= 0, Lambda >= 0,
    // complementary, has the unique solution Lambda = max(0, -b / g11).
    const double b = p.gdot_free[0] + p.restitution[0] * p.gdot_n_minus[0];
    impulse[0] = b >= 0.0 ? 0.0 : -b / g11;
    ++status_count_[static_cast<std::size_t>(lcp::Status::kSolved)];
  } else {
    // One result per index-set size: its vectors keep their size, so the workspace solver
    // allocates nothing once each size has been met.
    lcp::FrictionalResult& r = active_friction_ ? frictional_result_[static_cast<std::size_t>(k)]
                                                : frictionless_result_[static_cast<std::size_t>(k)];
    solver_.solve(p, options_.solver, solve_options_, options_.lcp_fallback, r);
    ++status_count_[static_cast<std::size_t>(r.status)];
    if (r.used_fallback) ++stats_.lcp_fallbacks;
    const bool usable = r.lambda_n.size() == k && r.lambda_n.allFinite() &&
                        (!active_friction_ || (r.lambda_t.size() == k && r.lambda_t.allFinite()));
    if (usable) {
      impulse.head(k) = r.lambda_n;
      if (active_friction_) impulse.tail(k) = r.lambda_t;
    } else {
      impulse.setZero();
    }
    if (!r.ok()) {
      // The answer is kept when it is finite (it is the solver's best iterate) and flagged:
      // a failed contact problem never passes silently.
      const std::string note = "contact problem not solved (" +
                               std::string(lcp::to_string(r.status)) + ", residual " +
                               std::to_string(r.residual) + ")" +
                               (usable ? "" : "; impulses set to zero");
      // Reported in full up to kMaxWarnings times; afterwards only counted in lcp_status.
      if (++unsolved_ <= kMaxWarnings) {
        recorder_.event(t_ + h, 0, EventKind::kWarning, note);
        stats_.warnings.push_back(note);
      }
    }
  }
  u_new_.noalias() += a_inv_w * impulse;
  for (int j = 0; j < k; ++j) {
    const int i = active_[static_cast<std::size_t>(j)];
    lambda_n_[i] = impulse[j];
    if (active_friction_) lambda_t_[i] = impulse[k + j];
  }
}

// Events from the step's impulses and end velocities (W and what of t_k):
//   impact: Lambda_N > 0 on a contact that was not resting and approached, gdot_N- < -v_tol;
//   close / open: the contact starts / stops resting (Lambda_N > 0 and |gdot_N+| <= v_tol;
//     a contact kept in the index set with no impulse and no separation velocity rests on);
//   stick / slip: a resting frictional contact's |gdot_T+| <= v_tol or not; slip is also
//     reported when the slip direction reverses.
void MoreauJean::update_events(double t1) {
  const double v_tol = options_.event_velocity_tolerance;
  for (int i = 0; i < m_; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const ContactData& c = contacts_[ui];
    const ContactState before = state_[ui];
    // An open contact without a normal impulse stays open: nothing to evaluate (most
    // contacts at most steps).
    if (before == ContactState::kOpen && !(lambda_n_[i] > 0.0)) continue;
    ContactState now = ContactState::kOpen;
    const bool resting = std::abs(c.gap_rate(u_new_)) <= v_tol;
    if (lambda_n_[i] > 0.0) {
      // A resting contact under a moving obstacle meets a small approach velocity every
      // step (the obstacle's acceleration times h): that is contact, not an impact.
      if (before == ContactState::kOpen && c.gap_rate(u_) < -v_tol) {
        recorder_.event(t1, i + 1, EventKind::kImpact);
      }
      if (resting) {
        const double slip = c.slip_rate(u_new_);
        if (c.friction == 0.0) {
          now = ContactState::kClosed;
        } else if (std::abs(slip) <= v_tol) {
          now = ContactState::kStick;
        } else {
          now = slip > 0.0 ? ContactState::kSlipPositive : ContactState::kSlipNegative;
        }
      }
    } else if (before != ContactState::kOpen && in_index_set_[ui] && resting) {
      now = before;
    }
    state_[ui] = now;
    if (now == before) continue;
    if (before == ContactState::kOpen) recorder_.event(t1, i + 1, EventKind::kClose);
    switch (now) {
      case ContactState::kOpen: recorder_.event(t1, i + 1, EventKind::kOpen); break;
      case ContactState::kClosed: break;
      case ContactState::kStick: recorder_.event(t1, i + 1, EventKind::kStick); break;
      case ContactState::kSlipPositive:
      case ContactState::kSlipNegative: recorder_.event(t1, i + 1, EventKind::kSlip); break;
    }
  }
}

// Works of the smooth forces by the trapezoidal rule on the powers at t_k and t_k+1.
void MoreauJean::accumulate_smooth_work(double h) {
  const PowerTerms p1 = system_.power(t_, q_, u_);
  energy_.damping += 0.5 * h * (power_k_.damping + p1.damping);
  energy_.ground += 0.5 * h * (power_k_.ground + p1.ground);
  energy_.external += 0.5 * h * (power_k_.external + p1.external);
  power_k_ = p1;
}

double MoreauJean::energy_error() {
  mu_tmp_.noalias() = mass_ * u_;
  const EnergyState e = system_.energy(t_, q_);
  energy_.kinetic = 0.5 * u_.dot(mu_tmp_);
  energy_.stored = e.stored;
  energy_.hysteretic = e.hysteretic;
  energy_.close();
  return energy_.error;
}

void MoreauJean::sample(bool force) {
  if (force) {
    recorder_.sample_now(t_, q_, u_, contacts_, force_n_, force_t_, energy_error());
    last_sample_t_ = t_;
  } else if (recorder_.due(t_)) {
    recorder_.sample(t_, q_, u_, contacts_, force_n_, force_t_, energy_error());
    last_sample_t_ = t_;
  }
}

}  // namespace

void MoreauJeanOptions::validate() const {
  if (!std::isfinite(end_time)) {
    throw std::invalid_argument("MoreauJeanOptions.end_time must be finite [s]");
  }
  if (!(step > 0.0) || !std::isfinite(step)) {
    throw std::invalid_argument("MoreauJeanOptions.step must be a finite number > 0 [s]");
  }
  if (!(theta >= 0.5 && theta <= 1.0)) {
    throw std::invalid_argument("MoreauJeanOptions.theta must be in [0.5, 1]");
  }
  if (!(lcp_tolerance > 0.0) || !std::isfinite(lcp_tolerance)) {
    throw std::invalid_argument("MoreauJeanOptions.lcp_tolerance must be a finite number > 0");
  }
  if (!(event_velocity_tolerance > 0.0) || !std::isfinite(event_velocity_tolerance)) {
    throw std::invalid_argument(
        "MoreauJeanOptions.event_velocity_tolerance must be a finite number > 0 [m/s]");
  }
  if (progress_interval <= 0) {
    throw std::invalid_argument("MoreauJeanOptions.progress_interval must be > 0");
  }
}

RunResult moreau_jean(System& system, const MoreauJeanOptions& options, Recorder& recorder) {
  MoreauJean integrator(system, options, recorder);
  return integrator.run();
}

}  // namespace nsb::integrators
