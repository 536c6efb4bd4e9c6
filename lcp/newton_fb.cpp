#include "lcp/newton_fb.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace nsb::lcp {

namespace {
// A Jacobian whose reciprocal condition estimate is below this is treated as singular: the
// Newton direction would carry no correct digits.
constexpr double kSingularRcond = 1e-14;
// The active-set trial: A = {i : z_i > w_i}. If A equals the previous estimate, solve
// M_AA z_A = -q_A and, if that z meets the tolerance, replace z and res and return true.
bool polish_step(const Problem& p, Vector& z, std::vector<char>& active,
                 std::vector<char>& previous, double& res, double tolerance) {
  const Eigen::Index n = p.size();
  const Vector w = p.M * z + p.q;
  std::vector<Eigen::Index> index;
  for (Eigen::Index i = 0; i < n; ++i) {
    active[static_cast<std::size_t>(i)] = z(i) > w(i) ? 1 : 0;
    if (active[static_cast<std::size_t>(i)]) index.push_back(i);
  }
  const bool same = active == previous;
  previous = active;
  if (!same) return false;
  const auto k = static_cast<Eigen::Index>(index.size());
  Vector trial = Vector::Zero(n);
  if (k > 0) {
    Matrix A(k, k);
    Vector b(k);
    for (Eigen::Index c = 0; c < k; ++c) {
      b(c) = -p.q(index[static_cast<std::size_t>(c)]);
      for (Eigen::Index r = 0; r < k; ++r)
        A(r, c) = p.M(index[static_cast<std::size_t>(r)], index[static_cast<std::size_t>(c)]);
    }
    const Eigen::PartialPivLU<Matrix> lu(A);
    const Vector x = lu.solve(b);
    if (!x.allFinite()) return false;
    for (Eigen::Index c = 0; c < k; ++c) trial(index[static_cast<std::size_t>(c)]) = std::max(0.0, x(c));
  }
  const double r = residual(p.M, p.q, trial);
  if (!(r <= tolerance)) return false;
  z = trial;
  res = r;
  return true;
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
  const Vector w = p.M * z + p.q;
  phi.resize(n);
  H.resize(n, n);
  Vector c = Vector::Zero(n);
  bool degenerate = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r = std::hypot(z(i), w(i));
    phi(i) = r - z(i) - w(i);
    if (r == 0.0) {
      c(i) = 1.0;
      degenerate = true;
    }
  }
  const Vector Mc = degenerate ? Vector(p.M * c) : Vector::Zero(n);
  Vector da(n);
  Vector db(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r = std::hypot(z(i), w(i));
    if (r > 0.0) {
      da(i) = z(i) / r - 1.0;
      db(i) = w(i) / r - 1.0;
    } else {
      // (0, 0): the limit along z + t c, with c_i = 1: s = sqrt(1 + (M c)_i^2).
      const double s = std::hypot(c(i), Mc(i));
      da(i) = c(i) / s - 1.0;
      db(i) = Mc(i) / s - 1.0;
    }
  }
  H.noalias() = db.asDiagonal() * p.M;
  H.diagonal() += da;
}

Result newton_fb(const Problem& p, const NewtonFbOptions& options, const Vector& warm_start) {
  p.validate();
  options.validate();
  const Eigen::Index n = p.size();
  Result r;
  const SolveClock clock(p);
  const auto finish = [&](Status s, std::string message) {
    return clock.finish(r, s, std::move(message));
  };
  r.z = warm_start.size() == n ? warm_start : Vector::Zero(n);
  Vector phi(n);
  Matrix H(n, n);
  Vector d(n);
  Vector trial(n);
  Vector phi_trial(n);
  Eigen::PartialPivLU<Matrix> lu(n);
  Vector w_trial(n);
  const auto merit = [&](const Vector& z, Vector& out) {
    Vector& w = w_trial;
    w.noalias() = p.M * z;
    w += p.q;
    for (Eigen::Index i = 0; i < n; ++i) out(i) = std::hypot(z(i), w(i)) - z(i) - w(i);
    return 0.5 * out.squaredNorm();
  };

  double res = residual(p.M, p.q, r.z);
  if (options.record_history) r.history.push_back(res);
  if (res <= options.tolerance) return finish(Status::kSolved, "the start point solves it");
  std::vector<char> active(static_cast<std::size_t>(n), 0);
  std::vector<char> previous(static_cast<std::size_t>(n), 2);  // 2: no estimate yet
  for (int k = 1; k <= options.max_iterations; ++k) {
    fischer_burmeister(p, r.z, phi, H);
    const double psi = 0.5 * phi.squaredNorm();
    const Vector grad = H.transpose() * phi;
    bool newton = false;
    lu.compute(H);
    if (lu.rcond() > kSingularRcond) {
      d = lu.solve(-phi);
      newton = d.allFinite() &&
               grad.dot(d) <= -options.descent_angle * grad.norm() * d.norm();
    }
    if (!newton) d = -grad;
    if (!(d.norm() > 0.0)) {
      r.iterations = k;
      return finish(Status::kSingularJacobian,
                    "stationary point of the merit function with Phi != 0: H^T Phi = 0");
    }
    // Armijo backtracking on Psi; the gradient step is tried when the Newton step fails.
    bool accepted = false;
    for (int attempt = 0; attempt < 2 && !accepted; ++attempt) {
      const double slope = grad.dot(d);
      double t = 1.0;
      for (int b = 0; b < options.max_backtracks; ++b) {
        trial = r.z + t * d;
        if (merit(trial, phi_trial) <= psi + options.armijo * t * slope) {
          accepted = true;
          break;
        }
        t *= options.backtrack;
      }
      if (!accepted && newton) {
        d = -grad;
        newton = false;
      } else {
        break;
      }
    }
    r.iterations = k;
    if (!accepted) {
      return finish(lu.rcond() > kSingularRcond ? Status::kLineSearchFailed
                                                : Status::kSingularJacobian,
                    "no step length gives sufficient decrease of 1/2 ||Phi||^2");
    }
    r.z = trial;
    res = residual(p.M, p.q, r.z);
    bool polished = false;
    if (options.polish && res > options.tolerance)
      polished = polish_step(p, r.z, active, previous, res, options.tolerance);
    if (options.record_history) r.history.push_back(res);
    if (polished) return finish(Status::kSolved, "converged (active-set solution)");
    if (res <= options.tolerance) return finish(Status::kSolved, "converged");
  }
  return finish(Status::kMaxIterations, "Newton step limit reached");
}

}  // namespace nsb::lcp
