#include "lcp/pgs.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace nsb::lcp {

void PgsOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("PgsOptions::tolerance must be finite and > 0");
  if (max_iterations < 1) throw std::invalid_argument("PgsOptions::max_iterations must be >= 1");
  if (!(relaxation > 0.0 && relaxation < 2.0))
    throw std::invalid_argument("PgsOptions::relaxation must be in (0, 2)");
}

Result pgs(const Problem& p, const PgsOptions& options, const Vector& warm_start) {
  p.validate();
  options.validate();
  const Eigen::Index n = p.size();
  Result r;
  const SolveClock clock(p);
  const auto finish = [&](Status s, std::string message) {
    return clock.finish(r, s, std::move(message));
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(p.M(i, i) > 0.0)) {
      std::ostringstream s;
      s << "M(" << i << ", " << i << ") = " << p.M(i, i)
        << " <= 0: the coordinate step is undefined";
      r.z = Vector::Zero(n);
      return finish(Status::kZeroDiagonal, s.str());
    }
  }
  r.z = warm_start.size() == n ? Vector(warm_start.cwiseMax(0.0)) : Vector::Zero(n);
  // A row-major copy makes the row products of a sweep contiguous; the residual uses the
  // column-major M for w = M z + q. Both are lcp::residual's formula.
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = p.M;
  const double scale = 1.0 + p.q.lpNorm<Eigen::Infinity>();
  Vector w(n);
  const auto current_residual = [&] {
    w.noalias() = p.M * r.z;
    w += p.q;
    const double v = r.z.cwiseMin(w).lpNorm<Eigen::Infinity>() / scale;
    return std::isnan(v) ? std::numeric_limits<double>::infinity() : v;
  };
  double res = n == 0 ? 0.0 : current_residual();
  if (options.record_history) r.history.push_back(res);
  if (res <= options.tolerance) return finish(Status::kSolved, "the start point solves it");
  const double omega = options.relaxation;
  for (int k = 1; k <= options.max_iterations; ++k) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double wi = rows.row(i).dot(r.z) + p.q(i);
      r.z(i) = std::max(0.0, r.z(i) - omega * wi / p.M(i, i));
    }
    r.iterations = k;
    res = current_residual();
    if (options.record_history) r.history.push_back(res);
    if (!std::isfinite(res)) return finish(Status::kMaxIterations, "the iterates diverged");
    if (res <= options.tolerance) return finish(Status::kSolved, "converged");
  }
  return finish(Status::kMaxIterations, "sweep limit reached");
}

}  // namespace nsb::lcp
