#include "lcp/lemke.hpp"

#include "lcp/fixed_size.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nsb::lcp {

namespace {
// Two ratios closer than this (relative to their size) are a tie for the lexicographic rule.
// Round-off in the tableau is a few ulps per pivot; 1e-11 leaves room for ~100 pivots of
// accumulated error while still separating genuinely different ratios of well-scaled data.
constexpr double kTieTolerance = 1e-11;
// A secondary ray is reported only when it is verified on the original data: the basic point
// (w, z, z0) >= 0 and the ray direction (dw, dz, dz0) >= 0 must satisfy w - M z - d z0 = q and
// dw - M dz - d dz0 = 0 to this relative tolerance (each violation divided by the size of
// the terms). Measured on 4451 ray terminations (Siconos's collection, M = -I, 4000 random
// eq. 6 bodies with eps = 0.5 and 3-4 contacts): the defects fall in two groups, <= 1e-12
// (1329 rays, most near 1e-15) and >= 1e-7 (3122, most between 1e-4 and 1: pivots on entries
// just above the pivot tolerance spoilt the tableau). 1e-9 lies three orders from each.
constexpr double kCertificateTolerance = 1e-9;
}  // namespace

int LemkeOptions::default_max_pivots(Eigen::Index n) {
  // A nondegenerate P-matrix problem rarely needs more than a few n pivots; Murty's example
  // needs 2^n (4096 at n = 12, the largest eq. 6 problem of the bridge). The cap keeps a
  // pathological problem from running unbounded.
  return static_cast<int>(std::max<Eigen::Index>(5000, 50 * (n + 1)));
}

void LemkeOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("LemkeOptions::tolerance must be finite and > 0");
  if (max_pivots < 0) throw std::invalid_argument("LemkeOptions::max_pivots must be >= 0");
  if (!(pivot_tolerance > 0.0) || !(pivot_tolerance <= 1e-3))
    throw std::invalid_argument("LemkeOptions::pivot_tolerance must be in (0, 1e-3]");
  for (Eigen::Index i = 0; i < covering.size(); ++i) {
    if (!(covering(i) > 0.0) || !std::isfinite(covering(i))) {
      std::ostringstream s;
      s << "LemkeOptions::covering(" << i << ") = " << covering(i) << "; must be finite and > 0";
      throw std::invalid_argument(s.str());
    }
  }
}

Lemke::Lemke(Eigen::Index capacity) { reserve(capacity); }

void Lemke::reserve(Eigen::Index n) {
  if (n <= capacity_) return;
  capacity_ = n;
  const auto un = static_cast<std::size_t>(n);
  tableau_.assign(un * (2 * un + 2), 0.0);
  column_.assign(un, 0.0);
  ratio_.assign(un, 0.0);
  lu_.assign(un * un, 0.0);
  rhs_.assign(un, 0.0);
  basis_.assign(un, 0);
  position_.assign(2 * un + 1, -1);
  candidates_.assign(un, 0);
  index_.assign(un, 0);
  w_.assign(un, 0.0);
}

// Selects the leaving row for the entering variable. For the first pivot (z0 entering, its
// column is -d) rows are ranked by (q_i, e_i^T) / d_i and the lexicographic minimum leaves:
// it is the most negative q_i / d_i. Afterwards only rows with a positive entry u_i of the
// entering column can block, ranked by (B^-1 q, B^-1)_i / u_i.
template <int N>
Eigen::Index Lemke::ratio_test(Eigen::Index entering, PivotKind kind) {
  const Eigen::Index n = fixed::size<N>(n_);
  const double* T = tableau_.data();
  const double* u = T + entering * n;
  const double* qcol = T + (2 * n + 1) * n;
  const bool initial = kind == PivotKind::kFirst;
  const double sign = initial ? -1.0 : 1.0;
  double unorm = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) unorm = std::max(unorm, std::abs(u[i]));
  const double threshold = pivot_tolerance_ * unorm;

  // Each ratio is divided once and kept for the tie test (infinite: the row cannot block).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double* ratio = ratio_.data();
  double best = kInf;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = sign * u[i];
    ratio[i] = s > threshold ? qcol[i] / s : kInf;
    best = std::min(best, ratio[i]);
  }
  if (!std::isfinite(best)) return -1;
  Eigen::Index count = 0;
  const double tie = kTieTolerance * (1.0 + std::abs(best));
  for (Eigen::Index i = 0; i < n; ++i)
    if (ratio[i] <= best + tie) candidates_[count++] = i;
  if (count == 1) return candidates_[0];
  // Prefer z0 leaving among tied rows: it ends the method at a solution.
  const Eigen::Index z0 = 2 * n;
  if (!initial) {
    for (Eigen::Index k = 0; k < count; ++k)
      if (basis_[candidates_[k]] == z0) return candidates_[k];
  }
  // Lexicographic tie-break on the columns of B^-1 (the tableau's w columns).
  for (Eigen::Index j = 0; j < n && count > 1; ++j) {
    const double* b = T + j * n;
    double lo = std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < count; ++k) {
      const Eigen::Index i = candidates_[k];
      lo = std::min(lo, b[i] / (sign * u[i]));
    }
    const double t = kTieTolerance * (1.0 + std::abs(lo));
    Eigen::Index kept = 0;
    for (Eigen::Index k = 0; k < count; ++k) {
      const Eigen::Index i = candidates_[k];
      if (b[i] / (sign * u[i]) <= lo + t) candidates_[kept++] = i;
    }
    count = kept;
  }
  return candidates_[0];
}

// Gauss–Jordan pivot on (row, entering). Basic columns are unit vectors and stay so; only
// the non-basic columns, the column of the leaving variable and q are updated.
template <int N>
void Lemke::pivot(Eigen::Index row, Eigen::Index entering) {
  const Eigen::Index n = fixed::size<N>(n_);
  double* T = tableau_.data();
  const Eigen::Index leaving = basis_[row];
  position_[leaving] = -1;
  position_[entering] = row;
  basis_[row] = entering;
  const Eigen::Index columns = 2 * n + 2;
  if constexpr (N > 0 && N <= 6) {
    // All 2N + 2 columns without tests: a basic column other than the entering one is a unit
    // vector e_r with r != row, so its multiplier a is 0 and x - 0 u leaves it as it is. At
    // these sizes the branch-free loop costs less than the tests that skip those columns.
    double u[N] = {};
    std::copy(T + entering * n, T + entering * n + n, u);
    const double inv = 1.0 / u[row];
    for (Eigen::Index v = 0; v < columns; ++v) {
      double* c = T + v * n;
      const double a = c[row] * inv;
      for (Eigen::Index i = 0; i < n; ++i) c[i] -= a * u[i];
      c[row] = a;
    }
    double* e = T + entering * n;
    std::fill(e, e + n, 0.0);
    e[row] = 1.0;
    return;
  }
  double* u = column_.data();
  std::copy(T + entering * n, T + entering * n + n, u);
  const double inv = 1.0 / u[row];
  for (Eigen::Index v = 0; v < columns; ++v) {
    if (v == entering || (v <= 2 * n && position_[v] >= 0)) continue;
    double* c = T + v * n;
    const double a = c[row] * inv;
    if (a == 0.0) continue;
    for (Eigen::Index i = 0; i < n; ++i) c[i] -= a * u[i];
    c[row] = a;
  }
  double* e = T + entering * n;
  std::fill(e, e + n, 0.0);
  e[row] = 1.0;
}

// Re-solves M_BB z_B = -q_B (B = basic z variables) by Gaussian elimination with partial
// pivoting on the original data, which removes the round-off the tableau accumulated.
// Returns false (z unchanged) if the block is numerically singular or the result leaves R+.
bool Lemke::refine(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                   Eigen::Ref<Vector> z) {
  const Eigen::Index n = n_;
  Eigen::Index k = 0;
  for (Eigen::Index j = 0; j < n; ++j)
    if (position_[n + j] >= 0) index_[k++] = j;
  if (k == 0) return false;
  double* A = lu_.data();
  double* b = rhs_.data();
  for (Eigen::Index c = 0; c < k; ++c)
    for (Eigen::Index r = 0; r < k; ++r) A[r + c * k] = M(index_[r], index_[c]);
  for (Eigen::Index r = 0; r < k; ++r) b[r] = -q(index_[r]);
  for (Eigen::Index c = 0; c < k; ++c) {
    Eigen::Index p = c;
    for (Eigen::Index r = c + 1; r < k; ++r)
      if (std::abs(A[r + c * k]) > std::abs(A[p + c * k])) p = r;
    if (!(std::abs(A[p + c * k]) > 0.0)) return false;
    if (p != c) {
      for (Eigen::Index cc = 0; cc < k; ++cc) std::swap(A[p + cc * k], A[c + cc * k]);
      std::swap(b[p], b[c]);
    }
    for (Eigen::Index r = c + 1; r < k; ++r) {
      const double f = A[r + c * k] / A[c + c * k];
      if (f == 0.0) continue;
      for (Eigen::Index cc = c; cc < k; ++cc) A[r + cc * k] -= f * A[c + cc * k];
      b[r] -= f * b[c];
    }
  }
  for (Eigen::Index r = k - 1; r >= 0; --r) {
    double s = b[r];
    for (Eigen::Index cc = r + 1; cc < k; ++cc) s -= A[r + cc * k] * b[cc];
    b[r] = s / A[r + r * k];
    if (!std::isfinite(b[r]) || b[r] < 0.0) return false;
  }
  for (Eigen::Index r = 0; r < k; ++r) z(index_[r]) = b[r];
  return true;
}

void Lemke::check(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                  Eigen::Index z_size) const {
  const Eigen::Index n = q.size();
  if (M.rows() != n || M.cols() != n || z_size != n)
    throw std::invalid_argument("Lemke::run: M must be n x n and z of size n, with n = q.size()");
}

Status Lemke::run(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                  const LemkeOptions& options, Eigen::Ref<Vector> z) {
  check(M, q, z.size());
  return fixed::dispatch(q.size(), [&](auto size) {
    return run_n<decltype(size)::value>(M, q, options, z);
  });
}

template <int N>
Status Lemke::run_n(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                    const LemkeOptions& options, Eigen::Ref<Vector> z) {
  const Eigen::Index n = fixed::size<N>(q.size());
  reserve(n);
  n_ = n;
  pivots_ = 0;
  residual_ = 0.0;
  pivot_tolerance_ = options.pivot_tolerance;
  double qmin = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) qmin = std::min(qmin, q(i));
  if (qmin >= 0.0) {  // z = 0, w = q >= 0 (also n = 0)
    z.setZero();
    for (Eigen::Index i = 0; i < n; ++i) w_[i] = q(i);
    return Status::kSolved;
  }
  load_tableau<N>(M, q, options);
  const int limit =
      options.max_pivots > 0 ? options.max_pivots : LemkeOptions::default_max_pivots(n);
  Eigen::Index entering = 2 * n;  // z0 enters first
  const Status status = complementary_pivots<N>(limit, entering);
  return read_solution<N>(M, q, options, status, entering, z);
}

// Tableau B^-1 [I, -M, -d, q] with B = I, written column by column; the basis is {w}.
template <int N>
inline void Lemke::load_tableau(const Eigen::Ref<const Matrix>& M,
                                const Eigen::Ref<const Vector>& q, const LemkeOptions& options) {
  const Eigen::Index n = fixed::size<N>(q.size());
  double* T = tableau_.data();
  std::fill(T, T + n * n, 0.0);
  for (Eigen::Index i = 0; i < n; ++i) T[i + i * n] = 1.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double* m = M.data() + j * M.outerStride();
    double* t = T + (n + j) * n;
    for (Eigen::Index i = 0; i < n; ++i) t[i] = -m[i];
  }
  const bool covered = options.covering.size() == n;
  for (Eigen::Index i = 0; i < n; ++i) T[i + 2 * n * n] = covered ? -options.covering(i) : -1.0;
  for (Eigen::Index i = 0; i < n; ++i) T[i + (2 * n + 1) * n] = q(i);
  for (Eigen::Index i = 0; i < n; ++i) basis_[i] = i;
  for (Eigen::Index v = 0; v <= 2 * n; ++v) position_[v] = v < n ? v : -1;
}

// Complementary pivoting: pivot the entering variable in, then let the complement of the
// one that left enter, until z0 leaves (kSolved), no row blocks (kRayTermination, entering
// is then the unblocked variable) or the pivot limit is reached (kMaxIterations).
template <int N>
inline Status Lemke::complementary_pivots(int limit, Eigen::Index& entering) {
  const Eigen::Index n = fixed::size<N>(n_);
  const Eigen::Index z0 = 2 * n;
  PivotKind kind = PivotKind::kFirst;
  while (true) {
    if (pivots_ >= limit) return Status::kMaxIterations;
    const Eigen::Index row = ratio_test<N>(entering, kind);
    if (row < 0) return Status::kRayTermination;
    const Eigen::Index leaving = basis_[row];
    pivot<N>(row, entering);
    ++pivots_;
    kind = PivotKind::kLater;
    if (leaving == z0) return Status::kSolved;
    entering = leaving < n ? leaving + n : leaving - n;  // the complement of the leaving one
  }
}

// z from the final basis (basic z_j = (B^-1 q)_r, clipped at 0), its residual, and the final
// status: a ray is confirmed on the original data, a solution refined when round-off shows.
template <int N>
inline Status Lemke::read_solution(const Eigen::Ref<const Matrix>& M,
                                   const Eigen::Ref<const Vector>& q, const LemkeOptions& options,
                                   Status status, Eigen::Index entering, Eigen::Ref<Vector> z) {
  const Eigen::Index n = fixed::size<N>(q.size());
  const double* qcol = tableau_.data() + (2 * n + 1) * n;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index r = position_[n + j];
    z(j) = r >= 0 ? std::max(0.0, qcol[r]) : 0.0;
  }
  residual_ = natural_residual<N>(M, q, z);
  if (status == Status::kRayTermination) {
    // z0 may have reached zero to round-off on the way (a tie with its exit that the ratio
    // test resolved the other way): then z already solves the LCP, and it is one.
    if (residual_ <= options.tolerance) return Status::kSolved;
    if (!ray_verified(M, q, options, entering)) return Status::kRoundOff;
    return status;
  }
  if (status == Status::kSolved && residual_ > options.tolerance) {
    // Keep the tableau answer unless the re-solve on the original data is better.
    for (Eigen::Index j = 0; j < n; ++j) column_[j] = z(j);
    const double before = residual_;
    if (refine(M, q, z)) {
      const double r2 = natural_residual<N>(M, q, z);
      if (!(r2 < before)) {
        for (Eigen::Index j = 0; j < n; ++j) z(j) = column_[j];
        residual_ = natural_residual<N>(M, q, z);
      } else {
        residual_ = r2;
      }
    }
    // z0 left the basis, so in exact arithmetic z solves the LCP: the excess is round-off.
    if (residual_ > options.tolerance) status = Status::kRoundOff;
  }
  return status;
}

// Checks the basic point and the ray direction of the entering column on the original data
// (see kCertificateTolerance). Raising the entering variable by t moves the basic variables
// to B^-1 q - t u, u the entering column of the tableau B^-1 [I, -M, -d, q].
bool Lemke::ray_verified(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                         const LemkeOptions& options, Eigen::Index entering) {
  const Eigen::Index n = n_;
  const double* T = tableau_.data();
  const double* u = T + entering * n;
  const double* qcol = T + (2 * n + 1) * n;
  const bool covered = options.covering.size() == n;
  // value(v, point): the basic point's (point = true) or the direction's component of v.
  const auto value = [&](Eigen::Index v, bool point) {
    const Eigen::Index r = position_[v];
    if (point) return r >= 0 ? qcol[r] : 0.0;
    if (v == entering) return 1.0;
    return r >= 0 ? -u[r] : 0.0;
  };
  double scale_point = 0.0;
  double scale_ray = 0.0;
  for (Eigen::Index v = 0; v <= 2 * n; ++v) {
    scale_point = std::max(scale_point, std::abs(value(v, true)));
    scale_ray = std::max(scale_ray, std::abs(value(v, false)));
  }
  for (Eigen::Index v = 0; v <= 2 * n; ++v) {
    if (value(v, true) < -kCertificateTolerance * (1.0 + scale_point)) return false;
    if (value(v, false) < -kCertificateTolerance * scale_ray) return false;
  }
  // Row i of w - M z - d z0 = q (point) and = 0 (direction), each against the size of its terms.
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = covered ? options.covering(i) : 1.0;
    for (const bool point : {true, false}) {
      double sum = value(i, point) - d * value(2 * n, point) - (point ? q(i) : 0.0);
      double size = std::abs(value(i, point)) + d * std::abs(value(2 * n, point)) +
                    (point ? std::abs(q(i)) : 0.0);
      for (Eigen::Index j = 0; j < n; ++j) {
        const double t = M(i, j) * value(n + j, point);
        sum -= t;
        size += std::abs(t);
      }
      if (std::abs(sum) > kCertificateTolerance * (point ? 1.0 + size : size)) return false;
    }
  }
  return true;
}

// r(z) of lcp::residual with w = M z + q kept in w_ (one product, column by column).
template <int N>
double Lemke::natural_residual(const Eigen::Ref<const Matrix>& M,
                               const Eigen::Ref<const Vector>& q, const Eigen::Ref<const Vector>& z) {
  const Eigen::Index n = fixed::size<N>(q.size());
  double* w = w_.data();
  double qmax = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    w[i] = q(i);
    qmax = std::max(qmax, std::abs(q(i)));
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    const double zj = z(j);
    if (zj == 0.0) continue;
    const double* m = M.data() + j * M.outerStride();
    for (Eigen::Index i = 0; i < n; ++i) w[i] += m[i] * zj;
  }
  double worst = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double v = std::abs(std::min(z(i), w[i]));
    if (!(v <= worst)) worst = std::isnan(v) ? std::numeric_limits<double>::infinity() : v;
  }
  return worst / (1.0 + qmax);
}

void Lemke::solve(const Problem& p, const LemkeOptions& options, Result& r) {
  const Eigen::Index n = p.size();
  if (p.M.rows() != n || p.M.cols() != n) p.validate();  // throws, naming the sizes
  fixed::dispatch(n, [&](auto size) { solve_n<decltype(size)::value>(p, options, r); });
}

// Validation (one pass over M and q), the pivoting, then both measures from the w that the
// residual of the run computed: no second product.
template <int N>
void Lemke::solve_n(const Problem& p, const LemkeOptions& options, Result& r) {
  const Eigen::Index n = fixed::size<N>(p.size());
  if constexpr (N > 0) {
    if (!fixed::finite<N>(p.M.data(), p.q.data(), n)) p.validate();  // throws, naming the entry
  } else {
    p.validate();
  }
  options.validate();
  if (options.covering.size() != 0 && options.covering.size() != n)
    throw std::invalid_argument("LemkeOptions::covering must be empty or of size n");
  // A reused Result keeps nothing of an earlier solve (clear() frees no memory).
  r.message.clear();
  r.wall_time = 0.0;
  r.history.clear();
  r.z.resize(n);
  r.status = run_n<N>(p.M, p.q, options, r.z);
  r.iterations = pivots_;
  r.w.resize(n);
  std::copy(w_.data(), w_.data() + n, r.w.data());
  fixed::measures<N>(p.q.data(), r.z.data(), r.w.data(), n, r.residual, r.siconos_error);
}

Result Lemke::solve(const Problem& p, const LemkeOptions& options) {
  const SolveClock clock;
  Result r;
  solve(p, options, r);
  return clock.finish(r);
}

Result lemke(const Problem& p, const LemkeOptions& options) {
  Lemke solver(p.size());
  return solver.solve(p, options);
}

}  // namespace nsb::lcp
