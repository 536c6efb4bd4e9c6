#include "lcp/newton_fb.hpp"

#include <cmath>
#include <stdexcept>

namespace nsb::lcp {

namespace {
// A Jacobian whose reciprocal condition estimate is below this is treated as singular: the
// Newton direction would carry no correct digits.
constexpr double kSingularRcond = 1e-14;
// The condition estimate (several triangular solves: a third of a step's cost at n = 26) runs
// only when the pivots of the LU spread over more than kPivotSpread. max |u_ii| / min |u_ii|
// is a lower bound on cond(U), not an upper one, so a factor with evenly sized pivots can still
// be nearly singular; such a factor is then treated as regular, and its direction still has to
// be finite, pass the angle test and pass the line search, which fall back to the gradient.
// 1e8 lies six orders of magnitude from 1 / kSingularRcond.
constexpr double kPivotSpread = 1e8;
constexpr double kInf = std::numeric_limits<double>::infinity();

// True unless the LU's reciprocal condition estimate is below kSingularRcond (see above).
template <class Lu>
bool regular(const Lu& lu) {
  const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
  if (pivots.size() == 0) return true;
  const double lo = pivots.minCoeff();
  const double hi = pivots.maxCoeff();
  if (lo > 0.0 && hi <= kPivotSpread * lo) return true;
  return lu.rcond() > kSingularRcond;
}

// Every vector and matrix one solve needs, sized once per solve. With Max = kSmall the
// storage is inside the object (no heap), with Max = Eigen::Dynamic on the heap.
template <int Max>
struct Workspace {
  using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, Max, Max>;
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, Max, 1>;
  using Index = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1, 0, Max, 1>;
  Vec z, w, z_full, w_full, phi, grad, d, trial, w_trial, phi_trial, da, db, x, b, rhs;
  Index active, tried, free;
  Mat H, A;
  Eigen::PartialPivLU<Mat> lu, lu_active;
  Eigen::CompleteOrthogonalDecomposition<Mat> cod_active;
  Eigen::Index tried_size = -1;

  void resize(Eigen::Index n) {
    for (Vec* v : {&z, &w, &z_full, &w_full, &phi, &grad, &d, &trial, &w_trial, &phi_trial,
                   &da, &db, &x, &b, &rhs})
      v->resize(n);
    active.resize(n);
    free.resize(n);
    tried.resize(n);
    H.resize(n, n);
    tried_size = -1;
  }
};

// out = M z + q, column by column.
template <class V>
void product(const Problem& p, const V& z, V& out) {
  const Eigen::Index n = p.size();
  out = p.q;
  for (Eigen::Index j = 0; j < n; ++j)
    if (z(j) != 0.0) out += z(j) * p.M.col(j);
}

// Phi from (z, w) and Psi = 1/2 ||Phi||^2.
template <class V>
double merit(const V& z, const V& w, V& phi) {
  double psi = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    phi(i) = std::hypot(z(i), w(i)) - z(i) - w(i);
    psi += phi(i) * phi(i);
  }
  return 0.5 * psi;
}

// lcp::residual from (z, w).
template <class V>
double natural(const V& z, const V& w, double scale) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double v = std::abs(std::min(z(i), w(i)));
    if (!(v <= worst)) worst = std::isnan(v) ? kInf : v;
  }
  return worst / scale;
}

// D_a, D_b of the header at (z, w), the degenerate (0, 0) pairs by the limit along c.
template <int Max, class V>
void jacobian_diagonals(const Problem& p, const V& z, Workspace<Max>& ws) {
  const Eigen::Index n = p.size();
  bool degenerate = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r = std::hypot(z(i), ws.w(i));
    if (r > 0.0) {
      ws.da(i) = z(i) / r - 1.0;
      ws.db(i) = ws.w(i) / r - 1.0;
    } else {
      degenerate = true;
    }
  }
  if (!degenerate) return;
  // c = indicator of the degenerate set; (M c)_i and s_i = sqrt(1 + (M c)_i^2) with c_i = 1.
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::hypot(z(i), ws.w(i)) > 0.0) continue;
    double mc = 0.0;
    for (Eigen::Index j = 0; j < n; ++j)
      if (std::hypot(z(j), ws.w(j)) == 0.0) mc += p.M(i, j);
    const double s = std::hypot(1.0, mc);
    ws.da(i) = 1.0 / s - 1.0;
    ws.db(i) = mc / s - 1.0;
  }
}

// The active-set trial: A = {i : z_i > w_i} for the given (z, w). If A differs from the last
// set tried, solve M_AA x = -q_A and form z_A = max(0, x), z_rest = 0 in ws.trial, with its w
// in ws.w_trial. Returns true if a trial point was formed.
template <int Max, class V>
bool active_set_trial(const Problem& p, const V& z, const V& w, Workspace<Max>& ws) {
  const Eigen::Index n = p.size();
  Eigen::Index k = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (z(i) > w(i)) ws.active(k++) = i;
  if (k == ws.tried_size && ws.active.head(k) == ws.tried.head(k)) return false;
  ws.tried.head(k) = ws.active.head(k);
  ws.tried_size = k;
  ws.trial.setZero();
  if (k > 0) {
    ws.A.resize(k, k);
    for (Eigen::Index c = 0; c < k; ++c) {
      ws.b(c) = -p.q(ws.active(c));
      for (Eigen::Index r = 0; r < k; ++r) ws.A(r, c) = p.M(ws.active(r), ws.active(c));
    }
    ws.lu_active.compute(ws.A);
    if (regular(ws.lu_active)) {
      ws.x.head(k) = ws.lu_active.solve(ws.b.head(k));
    } else {
      // A singular block (eq. 6 with more contacts than the body has degrees of freedom):
      // the least-norm solution, consistent if the support is right.
      ws.cod_active.compute(ws.A);
      ws.x.head(k) = ws.cod_active.solve(ws.b.head(k));
    }
    for (Eigen::Index c = 0; c < k; ++c) {
      if (!std::isfinite(ws.x(c))) return false;
      ws.trial(ws.active(c)) = std::max(0.0, ws.x(c));
    }
  }
  product(p, ws.trial, ws.w_trial);
  return true;
}

template <int Max>
Status iterate(const Problem& p, const NewtonFbOptions& options, Result& r, Workspace<Max>& ws);

// Runs the iteration and copies the iterate and its w into r.
template <int Max>
Status solve_with(const Problem& p, const NewtonFbOptions& options, Result& r,
                  Workspace<Max>& ws) {
  const Status s = iterate(p, options, r, ws);
  r.z = ws.z;
  r.w = ws.w;
  return s;
}

// The Newton direction H d = -Phi, H = D_a + D_b M, on the rows that need a linear solve. A row
// with D_b,ii = 0 (z_i = 0 and w_i > 0 exactly, where Phi_i = 0 and D_a,ii = -1: every inactive
// component of a point on the boundary, e.g. z = 0 or an active-set point) reads
// D_a,ii d_i = -Phi_i and gives d_i at once. The other rows F solve
//
//   (D_a + D_b M)_FF d_F = -Phi_F - D_b,F M_F,B d_B,
//
// the same direction as the full system, by an LU of |F| x |F| instead of n x n. Returns false
// if that block is singular (see regular()); ws.d is then unset.
template <int Max>
bool newton_direction(const Problem& p, Workspace<Max>& ws) {
  const Eigen::Index n = p.size();
  Eigen::Index k = 0;
  bool any_fixed = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (ws.db(i) != 0.0 || ws.da(i) == 0.0) {
      ws.free(k++) = i;
    } else {
      ws.d(i) = -ws.phi(i) / ws.da(i);
      any_fixed = true;
    }
  }
  if (k == n) {
    ws.H.resize(n, n);
    ws.H.noalias() = ws.db.asDiagonal() * p.M;
    ws.H.diagonal() += ws.da;
    ws.lu.compute(ws.H);
    if (!regular(ws.lu)) return false;
    ws.d = ws.lu.solve(-ws.phi);
    return true;
  }
  if (k == 0) return true;
  // With Max = kSmall the resize moves no memory; in the large workspace (n > kSmall) it
  // reallocates when the size of the block changes, as the active-set block A does.
  ws.H.resize(k, k);
  for (Eigen::Index c = 0; c < k; ++c) {
    const Eigen::Index j = ws.free(c);
    for (Eigen::Index r = 0; r < k; ++r) ws.H(r, c) = ws.db(ws.free(r)) * p.M(ws.free(r), j);
    ws.H(c, c) += ws.da(j);
  }
  for (Eigen::Index r = 0; r < k; ++r) ws.rhs(r) = -ws.phi(ws.free(r));
  if (any_fixed) {
    // - D_b,F M_F,B d_B, column by column over the fixed components with d_i != 0.
    for (Eigen::Index j = 0; j < n; ++j) {
      if (ws.db(j) != 0.0 || ws.da(j) == 0.0 || ws.d(j) == 0.0) continue;
      for (Eigen::Index r = 0; r < k; ++r)
        ws.rhs(r) -= ws.db(ws.free(r)) * p.M(ws.free(r), j) * ws.d(j);
    }
  }
  ws.lu.compute(ws.H);
  if (!regular(ws.lu)) return false;
  ws.x.head(k) = ws.lu.solve(ws.rhs.head(k));
  for (Eigen::Index r = 0; r < k; ++r) ws.d(ws.free(r)) = ws.x(r);
  return true;
}

// The search direction of one step at the current point: the Newton direction if H is regular,
// finite and within descent_angle of -grad Psi, else -grad Psi (grad Psi = H^T Phi = D_a Phi +
// M^T (D_b Phi)). Sets is_regular and newton (true: ws.d is the Newton direction).
template <int Max>
void search_direction(const Problem& p, const NewtonFbOptions& options, Workspace<Max>& ws,
                      bool& is_regular, bool& newton) {
  ws.rhs = ws.db.cwiseProduct(ws.phi);
  ws.grad.noalias() = p.M.transpose() * ws.rhs;
  ws.grad += ws.da.cwiseProduct(ws.phi);
  newton = false;
  is_regular = newton_direction(p, ws);
  if (is_regular) {
    newton = ws.d.allFinite() &&
             ws.grad.dot(ws.d) <= -options.descent_angle * ws.grad.norm() * ws.d.norm();
  }
  if (!newton) ws.d = -ws.grad;
}

// Armijo backtracking on Psi from ws.z along ws.d; the gradient step is tried when the Newton
// step fails. On success the accepted point is in ws.trial, ws.w_trial, ws.phi_trial and its
// merit in psi_trial. The first Newton trial (the full step) is kept in ws.z_full, ws.w_full.
template <int Max>
bool line_search(const Problem& p, const NewtonFbOptions& options, double psi, bool newton,
                 Workspace<Max>& ws, double& psi_trial) {
  bool accepted = false;
  psi_trial = kInf;
  for (int attempt = 0; attempt < 2 && !accepted; ++attempt) {
    const double slope = ws.grad.dot(ws.d);
    double t = 1.0;
    for (int b = 0; b < options.max_backtracks; ++b) {
      ws.trial = ws.z + t * ws.d;
      product(p, ws.trial, ws.w_trial);
      psi_trial = merit(ws.trial, ws.w_trial, ws.phi_trial);
      if (b == 0 && attempt == 0) {
        ws.z_full = ws.trial;
        ws.w_full = ws.w_trial;
      }
      if (psi_trial <= psi + options.armijo * t * slope) {
        accepted = true;
        break;
      }
      t *= options.backtrack;
    }
    if (!accepted && newton) {
      ws.d = -ws.grad;
      newton = false;
    } else {
      break;
    }
  }
  return accepted;
}

// Active-set points: from the support estimate of the iterate, then from that of the full
// (undamped) step, which identifies the support before the damped iterates do. Either is
// accepted if it lowers the merit function: the method stays monotone in Psi, and with the
// right support the point is the solution. Updates the iterate, psi and res in place.
template <int Max>
void polish_by_active_set(const Problem& p, const NewtonFbOptions& options, double scale,
                          Workspace<Max>& ws, double& psi, double& res) {
  auto& x = ws.z;
  for (int source = 0; source < 2 && options.polish && res > options.tolerance; ++source) {
    const bool formed = source == 0 ? active_set_trial(p, x, ws.w, ws)
                                    : active_set_trial(p, ws.z_full, ws.w_full, ws);
    if (!formed) continue;
    const double psi_a = merit(ws.trial, ws.w_trial, ws.phi_trial);
    if (psi_a < psi) {
      x = ws.trial;
      ws.w = ws.w_trial;
      ws.phi = ws.phi_trial;
      psi = psi_a;
      res = natural(x, ws.w, scale);
    }
  }
}

template <int Max>
Status iterate(const Problem& p, const NewtonFbOptions& options, Result& r, Workspace<Max>& ws) {
  const Eigen::Index n = p.size();
  ws.resize(n);
  const double scale = 1.0 + p.q.lpNorm<Eigen::Infinity>();
  // The iterate lives in the workspace (possibly inside the object) and goes back to r.z,
  // with its w, at the end.
  auto& x = ws.z;
  x = r.z;
  product(p, x, ws.w);
  double psi = merit(x, ws.w, ws.phi);
  double res = natural(x, ws.w, scale);
  if (options.record_history) r.history.push_back(res);
  if (res <= options.tolerance) return Status::kSolved;
  for (int k = 1; k <= options.max_iterations; ++k) {
    r.iterations = k;
    jacobian_diagonals(p, x, ws);
    bool is_regular = false;
    bool newton = false;
    search_direction(p, options, ws, is_regular, newton);
    if (!(ws.d.norm() > 0.0)) return Status::kSingularJacobian;
    double psi_trial = kInf;
    if (!line_search(p, options, psi, newton, ws, psi_trial))
      return is_regular ? Status::kLineSearchFailed : Status::kSingularJacobian;
    x = ws.trial;
    ws.w = ws.w_trial;
    ws.phi = ws.phi_trial;
    psi = psi_trial;
    res = natural(x, ws.w, scale);
    polish_by_active_set(p, options, scale, ws, psi, res);
    if (options.record_history) r.history.push_back(res);
    if (res <= options.tolerance) return Status::kSolved;
  }
  return Status::kMaxIterations;
}

}  // namespace

void NewtonFbOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("NewtonFbOptions::tolerance must be finite and > 0");
  if (max_iterations < 1)
    throw std::invalid_argument("NewtonFbOptions::max_iterations must be >= 1");
  if (!(armijo > 0.0 && armijo < 0.5))
    throw std::invalid_argument("NewtonFbOptions::armijo must be in (0, 0.5)");
  if (!(backtrack > 0.0 && backtrack < 1.0))
    throw std::invalid_argument("NewtonFbOptions::backtrack must be in (0, 1)");
  if (max_backtracks < 1)
    throw std::invalid_argument("NewtonFbOptions::max_backtracks must be >= 1");
  if (!(descent_angle > 0.0 && descent_angle < 1.0))
    throw std::invalid_argument("NewtonFbOptions::descent_angle must be in (0, 1)");
}

void fischer_burmeister(const Problem& p, const Vector& z, Vector& phi, Matrix& H) {
  const Eigen::Index n = p.size();
  Workspace<Eigen::Dynamic> ws;
  ws.resize(n);
  ws.z = z;
  product(p, ws.z, ws.w);
  phi.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) phi(i) = std::hypot(z(i), ws.w(i)) - z(i) - ws.w(i);
  jacobian_diagonals(p, z, ws);
  H.noalias() = ws.db.asDiagonal() * p.M;
  H.diagonal() += ws.da;
}

struct NewtonFb::Large : Workspace<Eigen::Dynamic> {};

NewtonFb::NewtonFb() = default;
NewtonFb::~NewtonFb() = default;
NewtonFb::NewtonFb(NewtonFb&&) noexcept = default;
NewtonFb& NewtonFb::operator=(NewtonFb&&) noexcept = default;

void NewtonFb::solve(const Problem& p, const NewtonFbOptions& options, Result& r,
                     const Vector& warm_start) {
  p.validate();
  options.validate();
  const Eigen::Index n = p.size();
  // A reused Result keeps nothing of an earlier solve (clear() frees no memory).
  r.message.clear();
  r.wall_time = 0.0;
  r.history.clear();
  r.iterations = 0;
  if (warm_start.size() == n) {
    r.z = warm_start;
  } else {
    r.z.resize(n);
    r.z.setZero();
  }
  if (n <= kSmall) {
    Workspace<kSmall> ws;
    r.status = solve_with(p, options, r, ws);
  } else {
    if (!large_) large_ = std::make_unique<Large>();
    r.status = solve_with(p, options, r, *large_);
  }
  evaluate_measures(p, r);
}

Result newton_fb(const Problem& p, const NewtonFbOptions& options, const Vector& warm_start) {
  const SolveClock clock;
  NewtonFb solver;
  Result r;
  solver.solve(p, options, r, warm_start);
  return clock.finish(r);
}

}  // namespace nsb::lcp
