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
    case Status::kZeroDiagonal: return "zero_diagonal";
    case Status::kSingularJacobian: return "singular_jacobian";
    case Status::kLineSearchFailed: return "line_search_failed";
    case Status::kNoSolution: return "no_solution";
    case Status::kTooLarge: return "too_large";
  }
  return "unknown";
}

double residual(const Matrix& M, const Vector& q, const Vector& z) {
  const Eigen::Index n = q.size();
  if (n == 0) return 0.0;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = M.row(i).dot(z) + q(i);
    const double v = std::abs(std::min(z(i), w));
    // NaN must not hide behind max(): a NaN iterate has an infinite residual.
    if (!(v <= worst)) worst = std::isnan(v) ? std::numeric_limits<double>::infinity() : v;
  }
  return worst / (1.0 + q.lpNorm<Eigen::Infinity>());
}

double siconos_error(const Matrix& M, const Vector& q, const Vector& z) {
  const Eigen::Index n = q.size();
  if (n == 0) return 0.0;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = M.row(i).dot(z) + q(i);
    const double d = z(i) - std::max(0.0, z(i) - w);
    sum += d * d;
  }
  const double qn = q.norm();
  const double e = std::sqrt(sum) / (qn > 0.0 ? qn : 1.0);
  return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
}

void evaluate(const Problem& p, Result& r) {
  if (r.z.size() != p.size()) {
    r.w.resize(0);
    r.residual = std::numeric_limits<double>::infinity();
    r.siconos_error = std::numeric_limits<double>::infinity();
    return;
  }
  r.w.noalias() = p.M * r.z;
  r.w += p.q;
  r.residual = residual(p.M, p.q, r.z);
  r.siconos_error = siconos_error(p.M, p.q, r.z);
}

SolveClock::SolveClock(const Problem& p)
    : problem_(p), start_(std::chrono::steady_clock::now()) {}

Result& SolveClock::finish(Result& r, Status s, std::string message) const {
  r.status = s;
  r.message = std::move(message);
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  evaluate(problem_, r);
  return r;
}

}  // namespace nsb::lcp
