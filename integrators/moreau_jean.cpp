#include "integrators/moreau_jean.hpp"

#include "integrators/contact_stage.hpp"
#include "integrators/run_bookkeeping.hpp"
#include "integrators/work_bounds.hpp"
#include "io/csv.hpp"

#include <Eigen/LU>

#include <algorithm>
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

// The step control of adaptive steps (docs/moreau-jean.md, "Adaptive steps"). The next step is
// h (kStepSafety / err)^(1/p) with err the local error estimate over the tolerance and p the
// local order of q (3 for theta = 1/2, 2 otherwise), kept within [kMinStepFactor,
// kMaxStepFactor] times h: the usual safety factor and bounds of a step controller (Hairer,
// Nørsett & Wanner, Solving ODEs I, sec. II.4), so that one poor estimate neither collapses
// nor explodes the step.
constexpr double kStepSafety = 0.8;
constexpr double kMinStepFactor = 0.2;
constexpr double kMaxStepFactor = 2.0;
// A step in which a contact impacts or changes state is retried with kSwitchFactor times its
// length, down to min_step (Studer, Leine & Glocker 2008: no error-based step in a switching
// step, the switching point localised by reducing the step).
constexpr double kSwitchFactor = 0.25;
// After a step was retried for a switch, the step does not grow again for this many accepted
// steps without a switch: the switch is near, and growing would only be rejected again.
constexpr int kLocalisingSteps = 8;
// A coordinate's error is measured against its peak so far, and at least against this
// fraction of the largest peak (weighted by the square root of the mass, which makes metres
// and radians comparable): a coordinate that barely moves is not asked for a relative
// accuracy on its round-off.
constexpr double kScaleFloor = 1e-2;
// The largest step when max_step is not given, in steps of the scene's own `step`, which
// resolves its excitation and its periods (runs/trust.hpp): the local estimate sees the error
// of the coordinates' smooth motion, not what falls between the steps of the forcing, and on
// the bridge longer steps leave an error of the peaks that no tolerance removes
// (docs/moreau-jean.md, "Adaptive steps").
constexpr double kMaxStepOfStep = 10.0;
// A growth below this factor is not taken (the step is held): each new length costs a
// factorization of A = M + h theta C + h^2 theta^2 K.
constexpr double kHoldGrowth = 1.25;

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
  bool march_fixed();
  bool march_adaptive();
  bool advance(double h, double t1);  // the end state of a step; false: non-finite
  double local_error(double h) const;
  bool switches(double h) const;
  ContactState end_state(int i, bool& impact) const;
  void resume(const MoreauJeanCheckpoint& from);
  void save(MoreauJeanCheckpoint& to) const;
  void factorize(double h);
  bool step(double h, double t1);  // false when the step failed (non-finite state)
  void free_velocity(double h);
  void select_index_set(double h);
  void accumulate_impulse_work();
  // false for a non-finite force or energy; force_ready: f(t1, q_k+1, u_k+1) is in f_end_,
  // the system's trial state is that evaluation's
  bool accept(double h, double t1, bool force_ready = false);
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

  // Adaptive steps: the last accepted step's mean acceleration (u_k - u_k-1) / h_k-1 and
  // length (has_previous_ false after a switching step: its velocity jumps), each
  // coordinate's peak |q| so far and sqrt(M_ii).
  Vector previous_rate_, peak_q_, root_mass_, f_end_;
  double previous_h_ = 0.0;
  bool has_previous_ = false;
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
  const bool adaptive = options_.local_tolerance > 0.0;
  const auto k = static_cast<std::int64_t>(std::llround((from.time - from.grid_origin) / h));
  const double on_grid = from.grid_origin + static_cast<double>(k) * h;
  if (!adaptive && !(k >= 0 && std::abs(on_grid - from.time) <= kTimeSlack * h)) {
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
  grid_origin_ = adaptive ? from.time : from.grid_origin;
  first_step_ = adaptive ? 0 : k;
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
  sample(true);
  const bool completed = options_.local_tolerance > 0.0 ? march_adaptive() : march_fixed();
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

// The steps of a fixed step h on the grid t_k = grid_origin + k h; false when the run ended
// before end_time.
bool MoreauJean::march_fixed() {
  const double t0 = grid_origin_;
  const double h = options_.step;
  const double duration = options_.end_time - t0;
  const auto steps = static_cast<std::int64_t>(std::ceil(duration / h - kTimeSlack));
  for (std::int64_t k = first_step_; k < steps; ++k) {
    const bool last = (k + 1 == steps);
    const double t1 = last ? options_.end_time : t0 + static_cast<double>(k + 1) * h;
    // Keep the nominal h (and its factorization) unless the last step is really shorter.
    const double hk = (last && std::abs((t1 - t_) - h) > kTimeSlack * h) ? t1 - t_ : h;
    if (!step(hk, t1)) return false;
    sample(last);
    book_.progress_at_interval(t_);
    if (book_.interrupted()) return false;
  }
  return true;
}

// Adaptive steps (docs/moreau-jean.md, "Adaptive steps"). Each trial step computes its end
// state from the committed state at t_k; it is retried, the system's trial state dropped,
// when a contact impacts or changes state in it and it is longer than min_step, or when its
// local error estimate exceeds the tolerance. An accepted step is an ordinary step of the
// scheme of its length: its impulses' work, its events, its commit and its sample, as with a
// fixed step. False when the run ended before end_time.
bool MoreauJean::march_adaptive() {
  const double end = options_.end_time;
  const double h_min = options_.min_step;
  const double h_max =
      std::min(options_.max_step > 0.0 ? options_.max_step : kMaxStepOfStep * options_.step,
               end - t_);
  const double order = theta_ == 0.5 ? 3.0 : 2.0;
  previous_rate_ = Vector::Zero(n_);
  f_end_ = Vector::Zero(n_);
  peak_q_ = q_.cwiseAbs();
  root_mass_ = mass_.diagonal().cwiseSqrt();
  has_previous_ = false;
  PaceWatch pace(t_, end);
  double h = std::clamp(options_.step, std::min(h_min, h_max), h_max);
  int localising = 0;  // accepted steps left without growth
  bool rejected = false;
  while (t_ < end) {
    const bool last = end - t_ <= h * (1.0 + kTimeSlack);
    const double t1 = last ? end : t_ + h;
    const double hk = last ? end - t_ : h;
    if (!advance(hk, t1)) return false;
    // The end state's force, evaluated here so that a hysteretic spring's change of branch
    // within the step (a kink of the force) counts as a switch; accept() keeps it.
    system_.forces(t1, q_new_, u_new_, f_end_);
    const bool switching = switches(hk) || system_.tangent_changed();
    const bool can_shrink = hk > h_min * (1.0 + kTimeSlack);
    if (switching && can_shrink) {
      system_.revert();
      ++book_.result().rejected_steps;
      h = std::max(h_min, kSwitchFactor * hk);
      localising = kLocalisingSteps;
      rejected = true;
      continue;
    }
    const double err = switching ? 0.0 : local_error(hk);
    if (err > 1.0 && can_shrink) {
      system_.revert();
      ++book_.result().rejected_steps;
      h = std::max(h_min,
                   hk * std::max(kMinStepFactor, kStepSafety * std::pow(err, -1.0 / order)));
      rejected = true;
      continue;
    }
    // Accepted: the rate of this step, for the next step's estimate (none across a switch,
    // where the velocity jumps).
    for (int i = 0; i < n_; ++i) previous_rate_[i] = (u_new_[i] - u_[i]) / hk;
    const bool had_previous = has_previous_;
    has_previous_ = !switching;
    previous_h_ = hk;
    accumulate_impulse_work();
    update_events(t1);
    if (!accept(hk, t1, true)) return false;
    for (int i = 0; i < n_; ++i) peak_q_[i] = std::max(peak_q_[i], std::abs(q_[i]));
    sample(last);
    if (std::string why = pace.collapsed(book_.result().steps, t_); !why.empty()) {
      book_.result().message = std::move(why);
      book_.stall(t_);
      return false;
    }
    book_.progress_at_interval(t_);
    if (book_.interrupted()) return false;
    if (last) break;
    // The next step: from the error where it is known, never growing right after a
    // rejection, a switch or without an estimate.
    double factor = err > 0.0 ? kStepSafety * std::pow(err, -1.0 / order) : kMaxStepFactor;
    factor = std::clamp(factor, kMinStepFactor, kMaxStepFactor);
    if (rejected || switching || !had_previous || localising > 0) factor = std::min(factor, 1.0);
    // A step that would grow by less than kHoldGrowth keeps its length, and so its
    // factorization of A (which depends on h).
    if (factor > 1.0 && factor < kHoldGrowth) factor = 1.0;
    if (switching) localising = 0;
    if (localising > 0) --localising;
    rejected = false;
    h = std::clamp(hk * factor, std::min(h_min, h_max), h_max);
  }
  return true;
}

// The local error of q over a trial step of length h, over the tolerance times each
// coordinate's scale, the largest over the coordinates (docs/moreau-jean.md, "The local error
// estimate"). The scheme's q_k+1 = q_k + h [(1 - theta) u_k + theta u_k+1] is the trapezoidal
// rule for theta = 1/2, with the local error -(h³/12) q‴ + O(h⁴); otherwise it adds
// (theta - 1/2) h² q″ + O(h³). q″ and q‴ = u″ come from the velocities of this step and the
// last: q″ ≈ (u_k+1 - u_k) / h, and u″ ≈ 2 [(u_k+1 - u_k) / h - (u_k - u_k-1) / h_k-1] /
// (h + h_k-1), the second divided difference. Without a last step (the first, or after a
// switch) only the term of theta - 1/2 is known.
// The peaks a run reports are the extremes over the ends of its steps (Recorder), so a step
// in which a velocity changes sign also counts the extremum it would miss: with u linear over
// the step, from a = |u_k| to b = |u_k+1|, the extremum lies h a² / (2 (a + b)) beyond q_k
// and h b² / (2 (a + b)) beyond q_k+1; the nearer end misses the smaller of the two.
double MoreauJean::local_error(double h) const {
  double largest_peak = 0.0;  // max_i sqrt(M_ii) max(peak_i, |q_i|)
  for (int i = 0; i < n_; ++i) {
    const double peak = std::max(peak_q_[i], std::abs(q_new_[i]));
    largest_peak = std::max(largest_peak, root_mass_[i] * peak);
  }
  if (!(largest_peak > 0.0)) return 0.0;  // at rest: nothing to be relative to
  const double first_order = std::abs(theta_ - 0.5) * h;
  double worst = 0.0;
  for (int i = 0; i < n_; ++i) {
    const double rate = (u_new_[i] - u_[i]) / h;
    double e = first_order * std::abs(u_new_[i] - u_[i]);
    if (has_previous_) {
      const double d2 = 2.0 * (rate - previous_rate_[i]) / (h + previous_h_);
      e += h * h * h / 12.0 * std::abs(d2);
    }
    if (u_[i] * u_new_[i] < 0.0) {
      const double a = std::abs(u_[i]), b = std::abs(u_new_[i]);
      e = std::max(e, 0.5 * h * std::min(a * a, b * b) / (a + b));
    }
    const double scale = std::max(std::max(peak_q_[i], std::abs(q_new_[i])),
                                  kScaleFloor * largest_peak / root_mass_[i]);
    worst = std::max(worst, e / (options_.local_tolerance * scale));
  }
  return worst;
}

// Whether a contact impacts or changes state (open, closed, stick, slip) at the end of the
// step of length h computed, without recording it: the switches update_events() would record;
// or whether a contact outside the index set closes within the step, its gap at t_k+1,
// g_N + h (gdot_N,k + gdot_N,k+1) / 2, below the gap's round-off (a long step passes the rule
// g_N + (h/2) gdot_N > 0 at t_k and would carry the body through the obstacle).
bool MoreauJean::switches(double h) const {
  const double gap_slack = ContactTolerances::gap(q_);
  for (int i = 0; i < m_; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const ContactData& c = contacts_[ui];
    if (!in_index_set_[ui] && !c.far &&
        c.gap_normal + 0.5 * h * (gap_rate(c, u_) + gap_rate(c, u_new_)) <= gap_slack) {
      return true;
    }
    const ContactState before = state_[ui];
    if (before == ContactState::kOpen && !(lambda_n_[i] > 0.0)) continue;
    bool impact = false;
    if (end_state(i, impact) != before || impact) return true;
  }
  return false;
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
  if (!advance(h, t1)) return false;
  accumulate_impulse_work();
  update_events(t1);
  return accept(h, t1);
}

// The end state (q_new_, u_new_) and the impulses of a step of length h from t_k to t1, from
// the committed state; the system is left at its trial state of the step.
bool MoreauJean::advance(double h, double t1) {
  if (refactor_ || h != h_factored_) factorize(h);
  system_.forces_on_committed_branches(t1, q_, u_, f_pred_);
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
  return true;
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
bool MoreauJean::accept(double h, double t1, bool force_ready) {
  if (force_ready) {
    copy(f_end_, f_k_);
  } else {
    system_.forces(t1, q_new_, u_new_, f_k_);
  }
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
// end_state() gives contact i's state at the end of the step computed and whether the step is
// an impact on it; update_events() records the changes.
ContactState MoreauJean::end_state(int i, bool& impact) const {
  const double v_tol = options_.event_velocity_tolerance;
  const auto ui = static_cast<std::size_t>(i);
  const ContactState before = state_[ui];
  const ContactData& c = in_index_set_[ui] ? contacts_next_[ui] : contacts_[ui];
  ContactState now = ContactState::kOpen;
  impact = false;
  const bool resting = std::abs(c.gap_rate(u_new_)) <= v_tol;
  if (lambda_n_[i] > 0.0) {
    // A resting contact under a moving obstacle meets a small approach velocity every
    // step (the obstacle's acceleration times h): that is contact, not an impact.
    impact = before == ContactState::kOpen && contacts_[ui].gap_rate(u_) < -v_tol;
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
  return now;
}

void MoreauJean::update_events(double t1) {
  for (int i = 0; i < m_; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const ContactState before = state_[ui];
    // An open contact without a normal impulse stays open: nothing to evaluate (most
    // contacts at most steps).
    if (before == ContactState::kOpen && !(lambda_n_[i] > 0.0)) continue;
    bool impact = false;
    const ContactState now = end_state(i, impact);
    if (impact) recorder_.impact(t1, i + 1, lambda_n_[i], lambda_t_[i]);
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
