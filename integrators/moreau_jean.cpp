#include "integrators/moreau_jean.hpp"

#include "integrators/contact_stage.hpp"
#include "integrators/run_bookkeeping.hpp"
#include "integrators/work_bounds.hpp"
#include "io/csv.hpp"

#include <Eigen/LU>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace nsb::integrators {

namespace {

// Relative slack when comparing times, so that round-off in end_time / h neither adds a
// spurious sliver of a step nor drops the last one.
constexpr double kTimeSlack = 1e-9;
// Unsolved contact problems reported one by one (events and RunResult::warnings); more are
// only counted, so a persistently failing solver cannot flood the outputs.
constexpr std::int64_t kMaxWarnings = 100;
// Accepted steps between two calls of the progress callback.
constexpr std::int64_t kProgressInterval = 4096;

// y += alpha A x. The systems here are tiny (3 DOF for the bridge), where the general
// matrix-vector kernel's dispatch costs more than the arithmetic. Per row the products are
// summed over the columns in order, then scaled by alpha and added, as Eigen's column-major
// kernel does (the bridge benchmark's histories came out bit for bit the same). The sums of
// all rows advance together, column by column (contiguous in column-major storage, so they
// vectorise), each row's in the same order.
template <int N>
void add_product_fixed(double alpha, const double* a, const double* x, double* y) {
  double s[N] = {};
  for (int j = 0; j < N; ++j) {
    for (int i = 0; i < N; ++i) s[i] += a[j * N + i] * x[j];
  }
  for (int i = 0; i < N; ++i) y[i] += s[i] * alpha;
}
// Any size; `sum` is a workspace of A's rows.
void add_product(double alpha, const Matrix& a, const Vector& x, Vector& sum, Vector& y) {
  const Eigen::Index rows = a.rows(), cols = a.cols();
  if (rows == cols) {
    switch (rows) {  // one body, two bodies (the bridges in parts)
      case 3: return add_product_fixed<3>(alpha, a.data(), x.data(), y.data());
      case 6: return add_product_fixed<6>(alpha, a.data(), x.data(), y.data());
      default: break;
    }
  }
  double* s = sum.data();
  for (Eigen::Index i = 0; i < rows; ++i) s[i] = 0.0;
  for (Eigen::Index j = 0; j < cols; ++j) {
    const double* col = a.data() + j * rows;
    const double xj = x[j];
    for (Eigen::Index i = 0; i < rows; ++i) s[i] += col[i] * xj;
  }
  for (Eigen::Index i = 0; i < rows; ++i) y[i] += s[i] * alpha;
}

// Element-wise loops for the vectors of the step (the same operations as Eigen's expressions,
// element by element, so the same numbers): for a few degrees of freedom, the dynamic-size
// expressions' setup costs more than the arithmetic.
// y = a x + b z
void combine(double a, const Vector& x, double b, const Vector& z, Vector& y) {
  const Eigen::Index n = y.size();
  for (Eigen::Index i = 0; i < n; ++i) y[i] = a * x[i] + b * z[i];
}
// y = x + a u + b w
void combine(const Vector& x, double a, const Vector& u, double b, const Vector& w, Vector& y) {
  const Eigen::Index n = y.size();
  for (Eigen::Index i = 0; i < n; ++i) y[i] = x[i] + a * u[i] + b * w[i];
}
void copy(const Vector& x, Vector& y) {
  const Eigen::Index n = y.size();
  for (Eigen::Index i = 0; i < n; ++i) y[i] = x[i];
}
bool all_finite(const Vector& x) {
  const Eigen::Index n = x.size();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) return false;
  }
  return true;
}
// gdot_N = W_N^T u + what_N. Up to three terms summed in order, which is Eigen's order for
// those sizes; Eigen's dot otherwise.
double gap_rate(const ContactData& c, const Vector& u) {
  const Vector& w = c.w_normal;
  switch (w.size()) {
    case 1: return w[0] * u[0] + c.what_normal;
    case 2: return (w[0] * u[0] + w[1] * u[1]) + c.what_normal;
    case 3: return (w[0] * u[0] + w[1] * u[1] + w[2] * u[2]) + c.what_normal;
    default: return c.gap_rate(u);
  }
}

class MoreauJean {
 public:
  MoreauJean(System& system, const MoreauJeanOptions& options, Recorder& recorder,
             const Progress& progress, const RunHooks& hooks);
  RunResult run();

 private:
  void resume(const MoreauJeanCheckpoint& from);
  void save(MoreauJeanCheckpoint& to) const;
  void factorize(double h);
  bool step(double h, double t1);  // false when the step failed (non-finite state)
  void free_velocity(double h);
  void select_index_set(double h);
  void accumulate_impulse_work();
  bool accept(double h, double t1);  // false for a non-finite force or energy
  bool solve_contacts(double t1);   // false for a non-finite contact problem
  bool diverge(double t1, const std::string& what);
  bool unseat(double t1);
  void update_events(double t1);
  void accumulate_smooth_work(double h);
  double energy_error();
  void sample(bool force);

  System& system_;
  const MoreauJeanOptions& options_;
  RunHooks hooks_;
  Recorder& recorder_;
  const Matrix& mass_;
  int n_ = 0;  // degrees of freedom
  int m_ = 0;  // potential contacts
  double theta_ = 0.5;

  // State at t_k, and the end-of-step values being computed. The steps fall at
  // t_k = grid_origin_ + k h, k from first_step_ (0 unless resumed).
  double t_ = 0.0;
  double grid_origin_ = 0.0;
  std::int64_t first_step_ = 0;
  Vector q_, u_, q_new_, u_new_, u_free_, rhs_, f_k_, f_pred_, mu_tmp_;

  // Tangent of the committed state and the iteration matrix A = M + h theta C + h^2 theta^2 K.
  Matrix K_, C_, A_, A_inv_, identity_;
  Eigen::PartialPivLU<Matrix> lu_;
  double h_factored_ = -1.0;
  bool refactor_ = true;
  bool has_stiffness_ = false;

  // Contacts: data at t_k (gaps, index set, Newton's law's gdot_N-) and at (t_k+1, q_k), where
  // the contact law is imposed (W and the rheonomic what of the moving seats); the index set.
  std::vector<ContactData> contacts_, contacts_next_;
  std::vector<int> active_;
  bool active_friction_ = false;
  ContactStage stage_;
  Vector lambda_n_, lambda_t_;  // impulses of every contact in this step [kN s]
  Vector force_n_, force_t_;    // lambda = Lambda / h, for the history [kN]
  bool had_impulses_ = false;   // lambda_n_, lambda_t_ may be non-zero (a contact problem)
  bool had_forces_ = false;     // force_n_, force_t_ may be non-zero
  std::vector<ContactState> state_;
  std::vector<char> in_index_set_;  // per contact: in the index set of this step

  // Energy bookkeeping: works accumulated since t0, and the powers at t_k.
  EnergyBalance energy_;
  PowerTerms power_k_;

  // The accepted step as the system sees it (System::accept_step): pointers to q_, u_ and
  // lambda_n_, set once.
  AcceptedStep accepted_;

  RunBookkeeping book_;
  double last_sample_t_ = -1e300;
};

MoreauJean::MoreauJean(System& system, const MoreauJeanOptions& options, Recorder& recorder,
                       const Progress& progress, const RunHooks& hooks)
    : system_(system),
      options_(options),
      hooks_(hooks),
      recorder_(recorder),
      mass_(system.mass()),
      n_(system.dofs()),
      m_(system.contacts()),
      theta_(options.theta),
      book_(MoreauJeanOptions::kMethod, progress, kProgressInterval) {
  options.validate();
  book_.watch(hooks.stop);
  checked_inverse_mass(system, "moreau_jean");
  // f_k_ holds f(t_k, q_k, u_k) at every recorded state (accept() evaluates it at t_k+1).
  recorder_.watch(&energy_, &f_k_);
  t_ = system.initial_time();
  q_ = system.initial_position();
  u_ = system.initial_velocity();
  grid_origin_ = t_;
  if (hooks.resume != nullptr) resume(*hooks.resume);
  if (!(options.end_time > t_)) {
    throw std::invalid_argument("moreau_jean: end_time (" + io::three_digits(options.end_time) +
                                ") must exceed the system's initial time (" +
                                io::three_digits(t_) + ")");
  }
  // The bound on the work of a run (integrators/work_bounds.hpp), for callers that bypass
  // the scene's check: "step: ..." names the key.
  if (!((options.end_time - t_) / options.step <= kMaxSteps)) {
    throw std::invalid_argument("step: " + io::three_digits(options.step) + " s to end_time " +
                                io::three_digits(options.end_time) + " s takes more than the " +
                                io::three_digits(kMaxSteps) + " steps a run may take");
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
  contacts_next_ = system.make_contact_buffer();
  active_.reserve(static_cast<std::size_t>(m_));
  ContactStageOptions stage_options;
  stage_options.solver = options.solver;
  stage_options.tolerance = options.lcp_tolerance;
  stage_options.fallback = options.lcp_fallback;
  stage_options.observer = hooks.contact_observer;
  stage_ = ContactStage(n_, m_, stage_options);
  lambda_n_ = Vector::Zero(m_);
  lambda_t_ = Vector::Zero(m_);
  force_n_ = Vector::Zero(m_);
  force_t_ = Vector::Zero(m_);
  state_.assign(static_cast<std::size_t>(m_), ContactState::kOpen);
  in_index_set_.assign(static_cast<std::size_t>(m_), 0);
  accepted_.q = &q_;
  accepted_.u = &u_;
  accepted_.normal_impulse = &lambda_n_;

  // The initial state is accepted as it is: evaluate and commit it, so that f_k, K and C
  // belong to the committed state at t0 (a resumed run's K and C are the saved ones).
  system_.forces(t_, q_, u_, f_k_);
  if (hooks.resume == nullptr) {
    system_.tangent(t_, q_, u_, K_, C_);
  } else {
    K_ = hooks.resume->stiffness;
    C_ = hooks.resume->damping;
  }
  system_.commit();
  system_.contact_data(t_, q_, u_, contacts_);
  if (static_cast<int>(contacts_.size()) != m_) {
    throw std::invalid_argument("moreau_jean: contact_data() did not fill contacts() entries");
  }
  power_k_ = system_.power(t_, q_, u_);
  const EnergyState e0 = system_.energy(t_, q_);
  mu_tmp_.noalias() = mass_ * u_;
  energy_.initial = 0.5 * u_.dot(mu_tmp_) + e0.stored;
  if (hooks.resume != nullptr) energy_ = hooks.resume->energy;
}

// Starts from a saved state (MoreauJeanCheckpoint): its time must lie on its grid,
// grid_origin + K h with K >= 0, as every step's end does, to within the round-off of an
// end_time that is not exactly on it (the saving run's last step then ended at end_time).
void MoreauJean::resume(const MoreauJeanCheckpoint& from) {
  const double h = options_.step;
  const auto k = static_cast<std::int64_t>(std::llround((from.time - from.grid_origin) / h));
  const double on_grid = from.grid_origin + static_cast<double>(k) * h;
  if (!(k >= 0 && std::abs(on_grid - from.time) <= kTimeSlack * h)) {
    throw std::invalid_argument("moreau_jean: resume.time (" + io::three_digits(from.time) +
                                ") is not on the step grid of resume.grid_origin (" +
                                io::three_digits(from.grid_origin) + ") and step");
  }
  if (from.position.size() != n_ || from.velocity.size() != n_ || !all_finite(from.position) ||
      !all_finite(from.velocity) || from.stiffness.rows() != n_ || from.stiffness.cols() != n_ ||
      from.damping.rows() != n_ || from.damping.cols() != n_) {
    throw std::invalid_argument("moreau_jean: resume: q and u must be finite vectors, K and C "
                                "matrices, of the system's dofs()");
  }
  t_ = from.time;
  q_ = from.position;
  u_ = from.velocity;
  grid_origin_ = from.grid_origin;
  first_step_ = k;
}

void MoreauJean::save(MoreauJeanCheckpoint& to) const {
  to.time = t_;
  to.position = q_;
  to.velocity = u_;
  to.grid_origin = grid_origin_;
  to.energy = energy_;
  to.stiffness = K_;
  to.damping = C_;
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
  ++book_.result().factorizations;
}

RunResult MoreauJean::run() {
  const double t0 = grid_origin_;
  const double h = options_.step;
  const double duration = options_.end_time - t0;
  const auto steps = static_cast<std::int64_t>(std::ceil(duration / h - kTimeSlack));

  sample(true);
  bool completed = true;
  for (std::int64_t k = first_step_; k < steps; ++k) {
    const bool last = (k + 1 == steps);
    const double t1 = last ? options_.end_time : t0 + static_cast<double>(k + 1) * h;
    // Keep the nominal h (and its factorization) unless the last step is really shorter.
    const double hk = (last && std::abs((t1 - t_) - h) > kTimeSlack * h) ? t1 - t_ : h;
    if (!step(hk, t1)) {
      completed = false;
      break;
    }
    sample(last);
    book_.progress_at_interval(t_);
    if (book_.interrupted()) {
      completed = false;
      break;
    }
  }
  if (completed) {
    book_.result().message = "reached end_time";
  } else if (last_sample_t_ != t_) {
    sample(true);
  }
  // The final energy balance.
  const double error = energy_error();
  if (!book_.diverged() && !std::isfinite(error)) {
    diverge(t_, "non-finite energy balance");
  }
  if (completed && !book_.diverged() && hooks_.checkpoint != nullptr) {
    save(*hooks_.checkpoint);
  }
  return book_.finish(t_, completed, energy_, &stage_.counts());
}

bool MoreauJean::diverge(double t1, const std::string& what) {
  system_.revert();
  book_.diverge(t1);
  RunResult& r = book_.result();
  r.message = what + " at t = " + io::three_digits(t1) +
              " s (the step or the model's forces are unstable)";
  recorder_.event(t1, 0, EventKind::kWarning, r.message);
  r.warnings.push_back(r.message);
  return false;
}

// The system stopped the run at the end of the accepted step t1 (a deck end unseated).
bool MoreauJean::unseat(double t1) {
  book_.unseat(t1);
  book_.result().message = "unseated at t = " + io::three_digits(t1) + " s";
  return false;
}

bool MoreauJean::step(double h, double t1) {
  if (refactor_ || h != h_factored_) factorize(h);
  system_.forces(t1, q_, u_, f_pred_);
  if (!all_finite(f_pred_)) return diverge(t1, "non-finite smooth force");
  free_velocity(h);
  select_index_set(h);
  copy(u_free_, u_new_);
  // The impulses of the previous step, if it had any, are cleared.
  if (had_impulses_) {
    lambda_n_.setZero();
    lambda_t_.setZero();
    had_impulses_ = false;
  }
  if (!active_.empty()) {
    had_impulses_ = true;
    if (!solve_contacts(t1)) return diverge(t1, "non-finite contact problem");
  }

  combine(q_, h * (1.0 - theta_), u_, h * theta_, u_new_, q_new_);
  if (!all_finite(q_new_) || !all_finite(u_new_)) return diverge(t1, "non-finite state");
  accumulate_impulse_work();
  update_events(t1);
  return accept(h, t1);
}

// Free velocity: the theta-method with the smooth force linearised about (q_k, u_k),
//   A (u_free - u_k) = h [(1-theta) f_k + theta f(t_k+1, q_k, u_k)] - h^2 theta K u_k,
// with f(t_k+1, q_k, u_k) in f_pred_.
void MoreauJean::free_velocity(double h) {
  combine(h * (1.0 - theta_), f_k_, h * theta_, f_pred_, rhs_);
  if (has_stiffness_) add_product(-(h * h * theta_), K_, u_, mu_tmp_, rhs_);
  copy(u_, u_free_);
  add_product(1.0, A_inv_, rhs_, mu_tmp_, u_free_);
}

// Index set: contacts closed or closing within the step, g_N + (h/2) gdot_N <= 0, with
// g_N and gdot_N at t_k (Acary & Brogliato 2008, ch. 10; Siconos uses the same rule). The
// comparison allows the round-off of g_N (ContactTolerances::gap), so that a resting
// contact whose gap came out at +1e-17 m is not dropped for one step.
void MoreauJean::select_index_set(double h) {
  const double gap_slack = ContactTolerances::gap(q_);
  active_.clear();
  for (int i = 0; i < m_; ++i) {
    const ContactData& c = contacts_[static_cast<std::size_t>(i)];
    in_index_set_[static_cast<std::size_t>(i)] = 0;
    if (c.far) continue;
    if (c.gap_normal + 0.5 * h * gap_rate(c, u_) <= gap_slack) {
      in_index_set_[static_cast<std::size_t>(i)] = 1;
      active_.push_back(i);
    }
  }
}

// Work of the contact impulses on the system over the step: Lambda . W^T (u_k + u_k+1)/2,
// the exact change of kinetic energy they cause (Acary & Brogliato 2008, ch. 10), with the
// columns W the impulses acted along (those of t_k+1).
void MoreauJean::accumulate_impulse_work() {
  for (int i : active_) {
    const ContactData& c = contacts_next_[static_cast<std::size_t>(i)];
    const double ln = lambda_n_[i];
    const double lt = lambda_t_[i];
    if (ln != 0.0) energy_.impacts += ln * 0.5 * (c.w_normal.dot(u_) + c.w_normal.dot(u_new_));
    if (lt != 0.0) energy_.friction += lt * 0.5 * (c.w_tangent.dot(u_) + c.w_tangent.dot(u_new_));
  }
}

// Accepts the step: evaluates the end state, keeps its tangent if it changed, commits once,
// hands the step with its impulses P_N to the system (System::accept_step: a removed contact
// is far in the contact data read next, so it leaves the index set), then the contact data,
// the works of the smooth forces and the forces for the history. False when the system
// stopped the run (unseated) or something went non-finite.
bool MoreauJean::accept(double h, double t1) {
  system_.forces(t1, q_new_, u_new_, f_k_);
  if (!all_finite(f_k_)) return diverge(t1, "non-finite smooth force");
  if (system_.tangent_changed()) {
    system_.tangent(t1, q_new_, u_new_, K_, C_);
    refactor_ = true;
  }
  system_.commit();
  std::swap(q_, q_new_);
  std::swap(u_, u_new_);
  t_ = t1;
  book_.count_step();
  accepted_.t = t1;
  accepted_.h = h;
  const StepVerdict verdict = system_.accept_step(accepted_);
  if (verdict == StepVerdict::kContactsRemoved) record_removed_contacts(system_, t1, recorder_);
  // Only the normal part: the index set of the next step, Newton's law's gdot_N- and the
  // events read nothing else at t_k (the contact problem uses the full data of t_k+1).
  system_.contact_normals(t_, q_, u_, contacts_);
  accumulate_smooth_work(h);
  if (!std::isfinite(energy_.damping + energy_.ground + energy_.external)) {
    return diverge(t1, "non-finite energy");
  }
  if (had_impulses_ || had_forces_) {
    for (int i = 0; i < m_; ++i) {
      force_n_[i] = lambda_n_[i] / h;
      force_t_[i] = lambda_t_[i] / h;
    }
    had_forces_ = had_impulses_;
  }
  if (verdict == StepVerdict::kUnseated) return unseat(t1);
  return true;
}

// The contact problem of the step, posed where Newton's law is imposed: on the relative
// velocity at t_k+1 (docs/moreau-jean.md, "The contact law at t_k+1"):
//   gdot_k+1 = W_k+1^T u_k+1 + what_k+1 = G Lambda + gdot_free,
//   G = W_k+1^T A^-1 W_k+1,  gdot_free = W_k+1^T u_free + what_k+1,
//   gdot_N,k+1 + eps gdot_N,k >= 0 _|_ Lambda_N >= 0,   gdot_N,k = W_N,k^T u_k + what_N,k,
// with W and what of the moving seats at t_k+1 (evaluated at q_k: the seats' motion is
// prescribed, so this costs one contact_data call on steps that have an index set).
bool MoreauJean::solve_contacts(double t1) {
  ++book_.result().steps_with_lcp;
  system_.contact_data(t1, q_, u_, contacts_next_);
  active_friction_ = false;
  for (int i : active_) {
    if (contacts_next_[static_cast<std::size_t>(i)].friction > 0.0) active_friction_ = true;
  }
  lcp::FrictionalProblem& p = stage_.build(contacts_next_, active_, active_friction_, A_inv_,
                                           u_free_, ContactLevel::kVelocity);
  const int k = static_cast<int>(active_.size());
  for (int j = 0; j < k; ++j) {
    p.gdot_n_minus[j] =
        gap_rate(contacts_[static_cast<std::size_t>(active_[static_cast<std::size_t>(j)])], u_);
  }
  const ContactStatus status = stage_.solve({ProblemKind::kStep, t1, book_.result().steps});
  if (status == ContactStatus::kNonFiniteInput) return false;
  if (status == ContactStatus::kUnsolved) {
    book_.note_unsolved(t1);
    // The best finite answer of the chain is kept and flagged: a failed contact problem
    // never passes silently. Reported in full up to kMaxWarnings times, then only counted.
    if (stage_.counts().unsolved <= kMaxWarnings) {
      const lcp::FrictionalResult& r = stage_.result();
      const std::string note = "contact problem not solved by any solver of the chain (last: " +
                               std::string(lcp::to_string(r.solver_used)) + ", " +
                               std::string(lcp::to_string(r.status)) + ", residual " +
                               io::three_digits(r.residual) + ")";
      recorder_.event(t1, 0, EventKind::kWarning, note);
      book_.result().warnings.push_back(note);
    }
  }
  stage_.apply(u_new_);
  for (int j = 0; j < k; ++j) {
    const int i = active_[static_cast<std::size_t>(j)];
    lambda_n_[i] = stage_.lambda_n(j);
    lambda_t_[i] = stage_.lambda_t(j);
  }
  return true;
}

// Events from the step's impulses and end velocities (W and what of t_k+1, where the contact
// law holds):
//   impact: Lambda_N > 0 on a contact that was not resting and approached, gdot_N- < -v_tol;
//   close / open: the contact starts / stops resting (Lambda_N > 0 and |gdot_N+| <= v_tol;
//     a contact kept in the index set with no impulse and no separation velocity rests on);
//   stick / slip: a resting frictional contact's |gdot_T+| <= v_tol or not; slip is also
//     reported when the slip direction reverses.
void MoreauJean::update_events(double t1) {
  const double v_tol = options_.event_velocity_tolerance;
  for (int i = 0; i < m_; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const ContactState before = state_[ui];
    // An open contact without a normal impulse stays open: nothing to evaluate (most
    // contacts at most steps).
    if (before == ContactState::kOpen && !(lambda_n_[i] > 0.0)) continue;
    const ContactData& c = in_index_set_[ui] ? contacts_next_[ui] : contacts_[ui];
    ContactState now = ContactState::kOpen;
    const bool resting = std::abs(c.gap_rate(u_new_)) <= v_tol;
    if (lambda_n_[i] > 0.0) {
      // A resting contact under a moving obstacle meets a small approach velocity every
      // step (the obstacle's acceleration times h): that is contact, not an impact.
      if (before == ContactState::kOpen && contacts_[ui].gap_rate(u_) < -v_tol) {
        recorder_.impact(t1, i + 1, lambda_n_[i], lambda_t_[i]);
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

// Every step's state enters the recorder's extremes (the run's peaks), recorded or not, so the
// energy balance is closed at every step.
void MoreauJean::sample(bool force) {
  const double error = energy_error();
  if (force) {
    recorder_.sample_now(t_, q_, u_, contacts_, force_n_, force_t_, error);
    last_sample_t_ = t_;
    return;
  }
  if (recorder_.due(t_)) last_sample_t_ = t_;
  recorder_.step(t_, q_, u_, contacts_, force_n_, force_t_, error);
}

}  // namespace

RunResult moreau_jean(System& system, const MoreauJeanOptions& options, Recorder& recorder,
                      const Progress& progress, const RunHooks& hooks) {
  MoreauJean integrator(system, options, recorder, progress, hooks);
  return integrator.run();
}

}  // namespace nsb::integrators
