#include "lcp/pgs.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace nsb::lcp {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// ||min(z, w)||_inf / scale from the maintained w; NaN reads as infinite.
double natural(const Vector& z, const Vector& w, double scale) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double v = std::abs(std::min(z(i), w(i)));
    if (!(v <= worst)) worst = std::isnan(v) ? kInf : v;
  }
  return worst / scale;
}

// w = M z + q, column by column.
void product(const Problem& p, const Vector& z, Vector& w) {
  const Eigen::Index n = p.size();
  w = p.q;
  for (Eigen::Index j = 0; j < n; ++j)
    if (z(j) != 0.0) w += z(j) * p.M.col(j);
}

// The sweeps on a start z >= 0 (r.z) with w = M z + q maintained in r.w: a coordinate step
// changes z_i by delta and w by delta M_.i, so w_i is read, not recomputed, and the residual
// costs O(n) per sweep. The maintained w drifts by round-off; before kSolved is reported, w is
// recomputed from z and the test repeated on it, so the reported residual is lcp::residual's.
Status sweep(const Problem& p, const PgsOptions& options, Result& r) {
  const Eigen::Index n = p.size();
  const double scale = 1.0 + p.q.lpNorm<Eigen::Infinity>();
  const double omega = options.relaxation;
  product(p, r.z, r.w);
  double res = natural(r.z, r.w, scale);
  if (options.record_history) r.history.push_back(res);
  if (res <= options.tolerance) return Status::kSolved;
  for (int k = 1; k <= options.max_iterations; ++k) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double zi = std::max(0.0, r.z(i) - omega * r.w(i) / p.M(i, i));
      const double delta = zi - r.z(i);
      if (delta == 0.0) continue;
      r.z(i) = zi;
      const double* c = p.M.data() + i * n;
      double* w = r.w.data();
      for (Eigen::Index j = 0; j < n; ++j) w[j] += delta * c[j];
    }
    r.iterations = k;
    res = natural(r.z, r.w, scale);
    if (!std::isfinite(res)) {
      if (options.record_history) r.history.push_back(res);
      return Status::kMaxIterations;
    }
    if (res <= options.tolerance) {
      product(p, r.z, r.w);  // remove the drift before deciding
      res = natural(r.z, r.w, scale);
    }
    if (options.record_history) r.history.push_back(res);
    if (res <= options.tolerance) return Status::kSolved;
  }
  return Status::kMaxIterations;
}
}  // namespace

void PgsOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("PgsOptions::tolerance must be finite and > 0");
  if (max_iterations < 1) throw std::invalid_argument("PgsOptions::max_iterations must be >= 1");
  if (!(relaxation > 0.0 && relaxation < 2.0))
    throw std::invalid_argument("PgsOptions::relaxation must be in (0, 2)");
}

void pgs(const Problem& p, const PgsOptions& options, Result& r) {
  p.validate();
  options.validate();
  const Eigen::Index n = p.size();
  // A reused Result keeps nothing of an earlier solve (clear() frees no memory).
  r.message.clear();
  r.wall_time = 0.0;
  r.history.clear();
  r.iterations = 0;
  r.z.resize(n);
  r.z.setZero();
  // The refusal is decided before any other work: a problem with M_ii <= 0 costs n reads.
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(p.M(i, i) > 0.0)) {
      r.status = Status::kZeroDiagonal;
      evaluate(p, r);
      return;
    }
  }
  r.w.resize(n);
  r.status = sweep(p, options, r);
  evaluate_measures(p, r);
}

Result pgs(const Problem& p, const PgsOptions& options, const Vector& warm_start) {
  const SolveClock clock;
  p.validate();
  options.validate();
  const Eigen::Index n = p.size();
  Result r;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(p.M(i, i) > 0.0)) {
      std::ostringstream s;
      s << "M(" << i << ", " << i << ") = " << p.M(i, i)
        << " <= 0: the coordinate step is undefined";
      r.z = Vector::Zero(n);
      r.status = Status::kZeroDiagonal;
      evaluate(p, r);
      return clock.finish(r, s.str());
    }
  }
  r.z = warm_start.size() == n ? Vector(warm_start.cwiseMax(0.0)) : Vector::Zero(n);
  r.w.resize(n);
  r.status = sweep(p, options, r);
  evaluate_measures(p, r);
  return clock.finish(r);
}

}  // namespace nsb::lcp
