#include "lcp/pgs.hpp"

#include "lcp/fixed_size.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace nsb::lcp {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// ||min(z, w)||_inf / scale from the maintained w; NaN reads as infinite.
template <int N>
double natural(const double* z, const double* w, Eigen::Index n_runtime, double scale) {
  const Eigen::Index n = fixed::size<N>(n_runtime);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double v = std::abs(std::min(z[i], w[i]));
    if (!(v <= worst)) worst = std::isnan(v) ? kInf : v;
  }
  return worst / scale;
}

// The sweeps on a start z >= 0 (r.z) with w = M z + q maintained in r.w: a coordinate step
// changes z_i by delta and w by delta M_.i, so w_i is read, not recomputed, and the residual
// costs O(n) per sweep. The maintained w drifts by round-off; before kSolved is reported, w is
// recomputed from z and the test repeated on it, so the reported residual is lcp::residual's.
// N: see lcp/fixed_size.hpp.
template <int N>
Status sweep(const Problem& p, const PgsOptions& options, Result& r) {
  const Eigen::Index n = fixed::size<N>(p.size());
  const double* M = p.M.data();
  const double* q = p.q.data();
  double* z = r.z.data();
  double* w = r.w.data();
  double qmax = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) qmax = std::max(qmax, std::abs(q[i]));
  const double scale = 1.0 + qmax;
  const double omega = options.relaxation;
  fixed::product<N>(M, n, q, z, w, n);
  double res = natural<N>(z, w, n, scale);
  if (options.record_history) r.history.push_back(res);
  if (res <= options.tolerance) return Status::kSolved;
  for (int k = 1; k <= options.max_iterations; ++k) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double zi = std::max(0.0, z[i] - omega * w[i] / M[i * n + i]);
      const double delta = zi - z[i];
      if (delta == 0.0) continue;
      z[i] = zi;
      const double* c = M + i * n;
      for (Eigen::Index j = 0; j < n; ++j) w[j] += delta * c[j];
    }
    r.iterations = k;
    res = natural<N>(z, w, n, scale);
    if (!std::isfinite(res)) {
      if (options.record_history) r.history.push_back(res);
      return Status::kMaxIterations;
    }
    if (res <= options.tolerance) {
      fixed::product<N>(M, n, q, z, w, n);  // remove the drift before deciding
      res = natural<N>(z, w, n, scale);
    }
    if (options.record_history) r.history.push_back(res);
    if (res <= options.tolerance) return Status::kSolved;
  }
  return Status::kMaxIterations;
}

// Index of the first diagonal entry that is not > 0, or n.
Eigen::Index first_nonpositive_diagonal(const Problem& p) {
  const Eigen::Index n = p.size();
  const double* M = p.M.data();
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(M[i * (n + 1)] > 0.0)) return i;
  return n;
}

// The refusal: z = 0, w = q and both measures of that point from q alone (M z = 0), in one
// pass: with z = 0, min(z, w)_i = min(0, q_i) and z_i - max(0, z_i - w_i) = min(0, q_i), so
// the measures are lcp::residual's and lcp::siconos_error's. The data read (the diagonal up to
// entry i, and q) are checked for finiteness: a non-finite one throws as Problem::validate
// does. The rest of M is neither read nor checked.
template <int N>
void refuse_n(const Problem& p, Eigen::Index i, Result& r) {
  const Eigen::Index n = fixed::size<N>(p.size());
  if (!std::isfinite(p.M(i, i))) p.validate();  // throws, naming the entry
  r.z.resize(n);
  r.w.resize(n);
  const double* q = p.q.data();
  double* z = r.z.data();
  double* w = r.w.data();
  double finite = 0.0;
  double worst = 0.0;
  double sum = 0.0;
  double qmax = 0.0;
  double qsum = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    z[k] = 0.0;
    w[k] = q[k];
    finite += q[k] * 0.0;
    const double m = std::min(0.0, q[k]);
    worst = std::max(worst, -m);
    sum += m * m;
    qmax = std::max(qmax, std::abs(q[k]));
    qsum += q[k] * q[k];
  }
  if (finite != 0.0) p.validate();  // a non-finite q: throws, naming the entry
  r.status = Status::kZeroDiagonal;
  r.residual = worst / (1.0 + qmax);
  const double qn = std::sqrt(qsum);
  r.siconos_error = std::sqrt(sum) / (qn > 0.0 ? qn : 1.0);
}

// Validation of the whole problem, then the sweeps from r.z (n-vector, >= 0) and both measures.
template <int N>
void solve_n(const Problem& p, const PgsOptions& options, Result& r) {
  const Eigen::Index n = fixed::size<N>(p.size());
  if constexpr (N > 0) {
    if (!fixed::finite<N>(p.M.data(), p.q.data(), n)) p.validate();  // throws, naming the entry
  } else {
    p.validate();
  }
  r.w.resize(n);
  r.status = sweep<N>(p, options, r);
  fixed::measures<N>(p.q.data(), r.z.data(), r.w.data(), n, r.residual, r.siconos_error);
}

// Shared by both forms: a bad size throws; a nonpositive diagonal entry is refused (returned
// as its index) before anything else is read; otherwise the sweeps run from start (or 0).
Eigen::Index run(const Problem& p, const PgsOptions& options, Result& r, const Vector* start) {
  const Eigen::Index n = p.size();
  if (p.M.rows() != n || p.M.cols() != n) p.validate();  // throws, naming the sizes
  options.validate();
  // A reused Result keeps nothing of an earlier solve (clear() frees no memory).
  r.message.clear();
  r.wall_time = 0.0;
  r.history.clear();
  r.iterations = 0;
  const Eigen::Index bad = first_nonpositive_diagonal(p);
  if (bad < n) {
    fixed::dispatch(n, [&](auto size) { refuse_n<decltype(size)::value>(p, bad, r); });
    return bad;
  }
  if (start != nullptr && start->size() == n) {
    r.z = start->cwiseMax(0.0);
  } else {
    r.z.resize(n);
    r.z.setZero();
  }
  fixed::dispatch(n, [&](auto size) { solve_n<decltype(size)::value>(p, options, r); });
  return n;
}
}  // namespace

void PgsOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("PgsOptions::tolerance must be finite and > 0");
  if (max_iterations < 1) throw std::invalid_argument("PgsOptions::max_iterations must be >= 1");
  if (!(relaxation > 0.0 && relaxation < 2.0))
    throw std::invalid_argument("PgsOptions::relaxation must be in (0, 2)");
}

void pgs(const Problem& p, const PgsOptions& options, Result& r) { run(p, options, r, nullptr); }

Result pgs(const Problem& p, const PgsOptions& options, const Vector& warm_start) {
  const SolveClock clock;
  Result r;
  const Eigen::Index bad = run(p, options, r, &warm_start);
  if (r.status != Status::kZeroDiagonal) return clock.finish(r);
  std::ostringstream s;
  s << "M(" << bad << ", " << bad << ") = " << p.M(bad, bad)
    << " <= 0: the coordinate step is undefined";
  return clock.finish(r, s.str());
}

}  // namespace nsb::lcp
