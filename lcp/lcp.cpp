#include "lcp/lcp.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nsb::lcp {

void Problem::validate() const {
  const Eigen::Index n = q.size();
  if (M.rows() != n || M.cols() != n) {
    std::ostringstream s;
    s << "lcp::Problem: M is " << M.rows() << " x " << M.cols() << " but q has size " << n
      << "; M must be " << n << " x " << n;
    throw std::invalid_argument(s.str());
  }
  // Fast path: 0 x is 0 for a finite x and NaN for NaN or +-inf, so one vectorised sum
  // decides; only a non-finite problem is searched entry by entry for the message.
  if ((M.array() * 0.0).sum() == 0.0 && (q.array() * 0.0).sum() == 0.0) return;
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!std::isfinite(M(i, j))) {
        std::ostringstream s;
        s << "lcp::Problem: M(" << i << ", " << j << ") = " << M(i, j)
          << "; every entry must be finite";
        throw std::invalid_argument(s.str());
      }
    }
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(q(i))) {
      std::ostringstream s;
      s << "lcp::Problem: q(" << i << ") = " << q(i) << "; every entry must be finite";
      throw std::invalid_argument(s.str());
    }
  }
}

std::string_view to_string(Status s) {
  switch (s) {
    case Status::kNotRun: return "not_run";
    case Status::kSolved: return "solved";
    case Status::kMaxIterations: return "max_iterations";
    case Status::kRayTermination: return "ray_termination";
    case Status::kRoundOff: return "round_off";
    case Status::kZeroDiagonal: return "zero_diagonal";
    case Status::kSingularJacobian: return "singular_jacobian";
    case Status::kLineSearchFailed: return "line_search_failed";
    case Status::kNoSolution: return "no_solution";
    case Status::kTooLarge: return "too_large";
  }
  return "unknown";
}

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// w = M z + q column by column (contiguous in column-major storage).
void product(const Matrix& M, const Vector& q, const Vector& z, double* w) {
  const Eigen::Index n = q.size();
  for (Eigen::Index i = 0; i < n; ++i) w[i] = q(i);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double zj = z(j);
    if (zj == 0.0) continue;
    const double* c = M.data() + j * n;
    for (Eigen::Index i = 0; i < n; ++i) w[i] += c[i] * zj;
  }
}

// Both measures from (z, w); NaN must not hide behind max(): a NaN iterate has an infinite
// residual and an infinite Siconos error.
void measures(const Vector& q, const double* z, const double* w, double* natural,
              double* siconos) {
  const Eigen::Index n = q.size();
  double worst = 0.0;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double v = std::abs(std::min(z[i], w[i]));
    if (!(v <= worst)) worst = std::isnan(v) ? kInf : v;
    const double d = z[i] - std::max(0.0, z[i] - w[i]);
    sum += d * d;
  }
  if (natural) *natural = n == 0 ? 0.0 : worst / (1.0 + q.lpNorm<Eigen::Infinity>());
  if (siconos) {
    const double qn = q.norm();
    const double e = n == 0 ? 0.0 : std::sqrt(sum) / (qn > 0.0 ? qn : 1.0);
    *siconos = std::isnan(e) ? kInf : e;
  }
}

// Small problems keep w on the stack; larger ones allocate (not a hot path of the solvers,
// which evaluate into Result::w).
constexpr Eigen::Index kStack = 32;

double measure(const Matrix& M, const Vector& q, const Vector& z, bool natural) {
  const Eigen::Index n = q.size();
  double out = 0.0;
  if (n <= kStack) {
    double w[kStack];
    product(M, q, z, w);
    measures(q, z.data(), w, natural ? &out : nullptr, natural ? nullptr : &out);
  } else {
    Vector w(n);
    product(M, q, z, w.data());
    measures(q, z.data(), w.data(), natural ? &out : nullptr, natural ? nullptr : &out);
  }
  return out;
}
}  // namespace

std::string_view describe(Status s) {
  switch (s) {
    case Status::kNotRun: return "the solver did not run";
    case Status::kSolved: return "solved: the residual meets the tolerance";
    case Status::kMaxIterations: return "iteration or pivot limit reached; z is the last iterate";
    case Status::kRayTermination:
      return "secondary ray: no solution found (none exists, or M is not in a class Lemke's "
             "method processes)";
    case Status::kRoundOff:
      return "round-off lost the pivoting path (tiny pivots, an infeasible basis, or a residual "
             "above the tolerance after refinement)";
    case Status::kZeroDiagonal: return "a diagonal entry of M is <= 0: the coordinate step is undefined";
    case Status::kSingularJacobian:
      return "stationary point of the merit function with Phi != 0, or a singular Jacobian "
             "without progress";
    case Status::kLineSearchFailed: return "no step length gives sufficient decrease of 1/2 ||Phi||^2";
    case Status::kNoSolution: return "no complementary basis solves the problem";
    case Status::kTooLarge: return "n exceeds the enumeration limit";
  }
  return "unknown status";
}

double residual(const Matrix& M, const Vector& q, const Vector& z) {
  return measure(M, q, z, true);
}

double siconos_error(const Matrix& M, const Vector& q, const Vector& z) {
  return measure(M, q, z, false);
}

void evaluate(const Problem& p, Result& r) {
  const Eigen::Index n = p.size();
  if (r.z.size() != n) {
    r.w.resize(0);
    r.residual = kInf;
    r.siconos_error = kInf;
    return;
  }
  r.w.resize(n);
  product(p.M, p.q, r.z, r.w.data());
  measures(p.q, r.z.data(), r.w.data(), &r.residual, &r.siconos_error);
}

void evaluate_measures(const Problem& p, Result& r) {
  if (r.z.size() != p.size() || r.w.size() != p.size()) {
    evaluate(p, r);
    return;
  }
  measures(p.q, r.z.data(), r.w.data(), &r.residual, &r.siconos_error);
}

SolveClock::SolveClock() : start_(std::chrono::steady_clock::now()) {}

Result& SolveClock::finish(Result& r) const { return finish(r, std::string(describe(r.status))); }

Result& SolveClock::finish(Result& r, std::string message) const {
  r.message = std::move(message);
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return r;
}

}  // namespace nsb::lcp
