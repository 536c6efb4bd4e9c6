#include "lcp/frictional.hpp"

#include "lcp/enumeration.hpp"
#include "lcp/newton_fb.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nsb::lcp {

namespace {

[[noreturn]] void bad(const std::string& field, Eigen::Index i, double value,
                      const char* allowed) {
  std::ostringstream s;
  s << "lcp::FrictionalProblem: " << field << "(" << i << ") = " << value << "; " << allowed;
  throw std::invalid_argument(s.str());
}

bool all_frictionless(const FrictionalProblem& fp) {
  return fp.frictionless() || fp.friction.isZero(0.0);
}

// Contact velocities for the impulses: gdot_N0 = G_NN l_N + G_NT l_T + gdot_N,free + eps gdot_N-
// and gdot_T+ = G_TN l_N + G_TT l_T + gdot_T,free (eqs. 3, 7, 8). No allocation.
template <class VN, class VT>
void contact_velocities(const FrictionalProblem& fp, const double* lambda_n,
                        const double* lambda_t, VN&& gdot_n0, VT&& gdot_t) {
  const Eigen::Index m = fp.contacts();
  const bool tangential = !fp.frictionless();
  for (Eigen::Index i = 0; i < m; ++i) {
    double s = fp.gdot_free(i) + fp.restitution(i) * fp.gdot_n_minus(i);
    for (Eigen::Index j = 0; j < m; ++j) {
      s += fp.delassus(i, j) * lambda_n[j];
      if (tangential) s += fp.delassus(i, m + j) * lambda_t[j];
    }
    gdot_n0(i) = s;
    if (tangential) {
      double t = fp.gdot_free(m + i);
      for (Eigen::Index j = 0; j < m; ++j)
        t += fp.delassus(m + i, j) * lambda_n[j] + fp.delassus(m + i, m + j) * lambda_t[j];
      gdot_t(i) = t;
    }
  }
}

// Diagonal shifts (relative to 1 + max |M_ii|) tried after a ray termination; see run_lemke.
constexpr double kRegularization[] = {1e-14, 1e-13, 1e-12};

double residual_raw(const FrictionalProblem& fp, const double* lambda_n, const double* lambda_t) {
  const Eigen::Index m = fp.contacts();
  const bool tangential = !fp.frictionless();
  double worst = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    double gn0 = fp.gdot_free(i) + fp.restitution(i) * fp.gdot_n_minus(i);
    double gt = tangential ? fp.gdot_free(m + i) : 0.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      gn0 += fp.delassus(i, j) * lambda_n[j];
      if (tangential) {
        gn0 += fp.delassus(i, m + j) * lambda_t[j];
        gt += fp.delassus(m + i, j) * lambda_n[j] + fp.delassus(m + i, m + j) * lambda_t[j];
      }
    }
    const double ln = lambda_n[i];
    const double lt = tangential ? lambda_t[i] : 0.0;
    const double bound = fp.friction(i) * std::max(0.0, ln);
    const double normal = std::abs(std::min(ln, gn0));
    const double cone = std::max(0.0, std::abs(lt) - fp.friction(i) * ln);
    const double dissipation = std::abs(lt - std::clamp(lt - gt, -bound, bound));
    for (double v : {normal, cone, dissipation}) {
      if (!(v <= worst)) worst = std::isnan(v) ? std::numeric_limits<double>::infinity() : v;
    }
  }
  double scale = 0.0;
  for (Eigen::Index i = 0; i < fp.gdot_free.size(); ++i)
    scale = std::max(scale, std::abs(fp.gdot_free(i)));
  return worst / (1.0 + scale);
}

}  // namespace

void FrictionalProblem::validate() const {
  const Eigen::Index m = contacts();
  const auto check_size = [&](const Vector& v, const char* name, Eigen::Index expected) {
    if (v.size() != expected) {
      std::ostringstream s;
      s << "lcp::FrictionalProblem: " << name << " has size " << v.size() << "; expected "
        << expected;
      throw std::invalid_argument(s.str());
    }
  };
  check_size(gdot_n_minus, "gdot_n_minus", m);
  check_size(friction, "friction", m);
  if (delassus.rows() != delassus.cols() || (delassus.rows() != m && delassus.rows() != 2 * m)) {
    std::ostringstream s;
    s << "lcp::FrictionalProblem: delassus is " << delassus.rows() << " x " << delassus.cols()
      << "; expected " << 2 * m << " x " << 2 * m << " (or " << m << " x " << m
      << " when frictionless) for " << m << " contacts";
    throw std::invalid_argument(s.str());
  }
  check_size(gdot_free, "gdot_free", delassus.rows());
  for (Eigen::Index j = 0; j < delassus.cols(); ++j)
    for (Eigen::Index i = 0; i < delassus.rows(); ++i)
      if (!std::isfinite(delassus(i, j))) {
        std::ostringstream s;
        s << "lcp::FrictionalProblem: delassus(" << i << ", " << j << ") = " << delassus(i, j)
          << "; every entry must be finite";
        throw std::invalid_argument(s.str());
      }
  for (Eigen::Index i = 0; i < gdot_free.size(); ++i)
    if (!std::isfinite(gdot_free(i))) bad("gdot_free", i, gdot_free(i), "must be finite");
  for (Eigen::Index i = 0; i < m; ++i) {
    if (!std::isfinite(gdot_n_minus(i))) bad("gdot_n_minus", i, gdot_n_minus(i), "must be finite");
    if (!(restitution(i) >= 0.0 && restitution(i) <= 1.0))
      bad("restitution", i, restitution(i), "must be in [0, 1]");
    if (!(friction(i) >= 0.0) || !std::isfinite(friction(i)))
      bad("friction", i, friction(i), "must be finite and >= 0");
    if (frictionless() && friction(i) != 0.0)
      bad("friction", i, friction(i),
          "must be 0 when the Delassus matrix is m x m (no tangential directions)");
  }
}

Eigen::Index eq6_size(const FrictionalProblem& fp) {
  return all_frictionless(fp) ? fp.contacts() : 3 * fp.contacts();
}

namespace {
// Writes eq. (6) into M (n x n, column-major with leading dimension n) and q. No allocation.
void write_eq6(const FrictionalProblem& fp, double* M, double* q) {
  const Eigen::Index m = fp.contacts();
  if (all_frictionless(fp)) {
    for (Eigen::Index j = 0; j < m; ++j)
      for (Eigen::Index i = 0; i < m; ++i) M[i + j * m] = fp.delassus(i, j);
    for (Eigen::Index i = 0; i < m; ++i)
      q[i] = fp.gdot_free(i) + fp.restitution(i) * fp.gdot_n_minus(i);
    return;
  }
  const Eigen::Index n = 3 * m;
  std::fill(M, M + n * n, 0.0);
  const auto at = [&](Eigen::Index i, Eigen::Index j) -> double& { return M[i + j * n]; };
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      const double mu = fp.friction(j);
      // Lambda_T = Lambda_TR - mu Lambda_N moves G_XT mu into the Lambda_N columns.
      at(i, j) = fp.delassus(i, j) - fp.delassus(i, m + j) * mu;
      at(i, m + j) = fp.delassus(i, m + j);
      at(m + i, j) = fp.delassus(m + i, j) - fp.delassus(m + i, m + j) * mu;
      at(m + i, m + j) = fp.delassus(m + i, m + j);
    }
    // gdot_TR+ = gdot_T+ + gdot_TL+ (eq. 4): the identity block E.
    at(m + i, 2 * m + i) = 1.0;
    // Lambda_TL = mu Lambda_N - Lambda_T = 2 mu Lambda_N - Lambda_TR (eq. 5).
    at(2 * m + i, i) = 2.0 * fp.friction(i);
    at(2 * m + i, m + i) = -1.0;
    q[i] = fp.gdot_free(i) + fp.restitution(i) * fp.gdot_n_minus(i);
    q[m + i] = fp.gdot_free(m + i);
    q[2 * m + i] = 0.0;
  }
}

// Fills result.lambda_n/t and the post-impact velocities from eq. (6)'s z.
void read_eq6_into(const FrictionalProblem& fp, const double* z, FrictionalResult& r) {
  const Eigen::Index m = fp.contacts();
  r.lambda_n.resize(m);
  r.lambda_t.resize(m);
  r.gdot_n_plus.resize(m);
  r.gdot_t_plus.resize(m);
  r.lambda_t.setZero();
  for (Eigen::Index i = 0; i < m; ++i) r.lambda_n(i) = z[i];
  if (!all_frictionless(fp)) {
    for (Eigen::Index i = 0; i < m; ++i) r.lambda_t(i) = z[m + i] - fp.friction(i) * z[i];
  }
  contact_velocities(fp, r.lambda_n.data(), r.lambda_t.data(), r.gdot_n_plus, r.gdot_t_plus);
  // gdot_N+ = gdot_N0 - eps gdot_N- (eq. 3's complementarity variable back to gdot_N+).
  for (Eigen::Index i = 0; i < m; ++i) r.gdot_n_plus(i) -= fp.restitution(i) * fp.gdot_n_minus(i);
  if (fp.frictionless()) r.gdot_t_plus.setZero();
  r.residual = residual_raw(fp, r.lambda_n.data(), r.lambda_t.data());
}
}  // namespace

Problem build_eq6(const FrictionalProblem& fp) {
  fp.validate();
  const Eigen::Index n = eq6_size(fp);
  Problem p;
  p.M.resize(n, n);
  p.q.resize(n);
  write_eq6(fp, p.M.data(), p.q.data());
  return p;
}

FrictionalResult read_eq6(const FrictionalProblem& fp, const Vector& z) {
  fp.validate();
  if (z.size() != eq6_size(fp)) {
    std::ostringstream s;
    s << "lcp::read_eq6: z has size " << z.size() << "; expected " << eq6_size(fp);
    throw std::invalid_argument(s.str());
  }
  FrictionalResult r;
  read_eq6_into(fp, z.data(), r);
  return r;
}

double frictional_residual(const FrictionalProblem& fp, const Vector& lambda_n,
                           const Vector& lambda_t) {
  fp.validate();
  const Eigen::Index m = fp.contacts();
  if (lambda_n.size() != m || (lambda_t.size() != m && !(fp.frictionless() && lambda_t.size() == 0)))
    throw std::invalid_argument("lcp::frictional_residual: lambda_n and lambda_t must have size m");
  const Vector zero = Vector::Zero(m);
  return residual_raw(fp, lambda_n.data(), lambda_t.size() == m ? lambda_t.data() : zero.data());
}

namespace {
// The natural-form PGS on raw storage: lambda = [Lambda_N; Lambda_T] (size 2m). No allocation.
Status pgs_natural(const FrictionalProblem& fp, const PgsOptions& o, double* lambda,
                   int& sweeps, double& res) {
  const Eigen::Index m = fp.contacts();
  const bool tangential = !fp.frictionless();
  double* ln = lambda;
  double* lt = lambda + m;
  for (Eigen::Index i = 0; i < m; ++i) {
    if (!(fp.delassus(i, i) > 0.0)) return Status::kZeroDiagonal;
    if (tangential && fp.friction(i) > 0.0 && !(fp.delassus(m + i, m + i) > 0.0))
      return Status::kZeroDiagonal;
  }
  sweeps = 0;
  res = residual_raw(fp, ln, lt);
  if (res <= o.tolerance) return Status::kSolved;
  const double omega = o.relaxation;
  for (int k = 1; k <= o.max_iterations; ++k) {
    for (Eigen::Index i = 0; i < m; ++i) {
      double gn0 = fp.gdot_free(i) + fp.restitution(i) * fp.gdot_n_minus(i);
      for (Eigen::Index j = 0; j < m; ++j) {
        gn0 += fp.delassus(i, j) * ln[j];
        if (tangential) gn0 += fp.delassus(i, m + j) * lt[j];
      }
      ln[i] = std::max(0.0, ln[i] - omega * gn0 / fp.delassus(i, i));
      if (!tangential) continue;
      const double bound = fp.friction(i) * ln[i];
      if (bound == 0.0) {
        lt[i] = 0.0;
        continue;
      }
      double gt = fp.gdot_free(m + i);
      for (Eigen::Index j = 0; j < m; ++j)
        gt += fp.delassus(m + i, j) * ln[j] + fp.delassus(m + i, m + j) * lt[j];
      lt[i] = std::clamp(lt[i] - omega * gt / fp.delassus(m + i, m + i), -bound, bound);
    }
    sweeps = k;
    res = residual_raw(fp, ln, lt);
    if (!std::isfinite(res)) return Status::kMaxIterations;
    if (res <= o.tolerance) return Status::kSolved;
  }
  return Status::kMaxIterations;
}

void finish_natural(const FrictionalProblem& fp, const double* lambda, FrictionalResult& r) {
  const Eigen::Index m = fp.contacts();
  r.lambda_n.resize(m);
  r.lambda_t.resize(m);
  r.gdot_n_plus.resize(m);
  r.gdot_t_plus.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    r.lambda_n(i) = lambda[i];
    r.lambda_t(i) = fp.frictionless() ? 0.0 : lambda[m + i];
  }
  contact_velocities(fp, r.lambda_n.data(), r.lambda_t.data(), r.gdot_n_plus, r.gdot_t_plus);
  for (Eigen::Index i = 0; i < m; ++i) r.gdot_n_plus(i) -= fp.restitution(i) * fp.gdot_n_minus(i);
  if (fp.frictionless()) r.gdot_t_plus.setZero();
}
}  // namespace

FrictionalResult pgs_frictional(const FrictionalProblem& fp, const PgsOptions& options,
                                const Vector& lambda_n0, const Vector& lambda_t0) {
  fp.validate();
  options.validate();
  const Eigen::Index m = fp.contacts();
  std::vector<double> lambda(static_cast<std::size_t>(2 * m), 0.0);
  if (lambda_n0.size() == m)
    for (Eigen::Index i = 0; i < m; ++i) lambda[i] = std::max(0.0, lambda_n0(i));
  if (lambda_t0.size() == m && !fp.frictionless())
    for (Eigen::Index i = 0; i < m; ++i)
      lambda[m + i] = std::clamp(lambda_t0(i), -fp.friction(i) * lambda[i],
                                 fp.friction(i) * lambda[i]);
  FrictionalResult r;
  r.solver_used = Solver::kPgs;
  double res = 0.0;
  r.status = pgs_natural(fp, options, lambda.data(), r.iterations, res);
  finish_natural(fp, lambda.data(), r);
  r.residual = res;
  if (r.status == Status::kZeroDiagonal) r.residual = std::numeric_limits<double>::infinity();
  return r;
}

FrictionalSolver::FrictionalSolver(Eigen::Index max_contacts) { reserve(max_contacts); }

void FrictionalSolver::reserve(Eigen::Index contacts) {
  if (contacts <= capacity_) return;
  capacity_ = contacts;
  const auto n = static_cast<std::size_t>(3 * contacts);
  matrix_.assign(n * n, 0.0);
  q_.assign(n, 0.0);
  z_.assign(n, 0.0);
  lambda_.assign(2 * static_cast<std::size_t>(contacts), 0.0);
  lemke_.reserve(3 * contacts);
}

void FrictionalSolver::assemble(const FrictionalProblem& fp, Eigen::Index) {
  write_eq6(fp, matrix_.data(), q_.data());
}

void FrictionalSolver::run_lemke(const FrictionalProblem& fp, const SolveOptions& options,
                                 FrictionalResult& result) {
  const Eigen::Index n = eq6_size(fp);
  assemble(fp, n);
  Eigen::Map<Matrix> M(matrix_.data(), n, n);
  const Eigen::Map<const Vector> q(q_.data(), n);
  Eigen::Map<Vector> z(z_.data(), n);
  LemkeOptions o;
  o.tolerance = options.tolerance;
  o.max_pivots = options.max_iterations;
  result.status = lemke_.run(M, q, o, z);
  result.iterations = lemke_.pivots();
  if (result.status == Status::kRayTermination || result.status == Status::kRoundOff) {
    // A body wedged between contacts whose impulses can balance (W d = 0, d >= 0) with
    // q^T d = 0 exactly (eps = 0, or no rebound along d) has an unbounded solution set, and
    // round-off can then end Lemke's path on a (spurious) secondary ray or lose it. Retry with M + delta I, which
    // makes the solution set bounded; accept the answer only if it solves the original
    // problem: delta z must stay below the tolerance, hence the tiny delta.
    double scale = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) scale = std::max(scale, std::abs(M(i, i)));
    int total = result.iterations;
    for (const double factor : kRegularization) {
      assemble(fp, n);
      for (Eigen::Index i = 0; i < n; ++i) M(i, i) += factor * (1.0 + scale);
      const Status s = lemke_.run(M, q, o, z);
      total += lemke_.pivots();
      assemble(fp, n);
      if (s == Status::kSolved && residual(M, q, z) <= options.tolerance) {
        result.status = Status::kSolved;
        break;
      }
    }
    result.iterations = total;
  }
  result.solver_used = Solver::kLemke;
  read_eq6_into(fp, z_.data(), result);
}

void FrictionalSolver::solve(const FrictionalProblem& fp, Solver solver,
                             const SolveOptions& options, FrictionalResult& result) {
  fp.validate();
  options.validate();
  reserve(fp.contacts());
  result.status = Status::kNotRun;
  switch (solver) {
    case Solver::kLemke:
      run_lemke(fp, options, result);
      return;
    case Solver::kPgs: {
      PgsOptions o;
      o.tolerance = options.tolerance;
      if (options.max_iterations > 0) o.max_iterations = options.max_iterations;
      std::fill(lambda_.begin(), lambda_.end(), 0.0);
      double res = 0.0;
      result.solver_used = Solver::kPgs;
      result.status = pgs_natural(fp, o, lambda_.data(), result.iterations, res);
      finish_natural(fp, lambda_.data(), result);
      result.residual =
          result.status == Status::kZeroDiagonal ? std::numeric_limits<double>::infinity() : res;
      break;
    }
    case Solver::kNewtonFb:
    case Solver::kEnumeration: {
      const Eigen::Index n = eq6_size(fp);
      eq6_.M.resize(n, n);
      eq6_.q.resize(n);
      write_eq6(fp, eq6_.M.data(), eq6_.q.data());
      Result& r = eq6_result_;
      if (solver == Solver::kNewtonFb) {
        NewtonFbOptions o;
        o.tolerance = options.tolerance;
        if (options.max_iterations > 0) o.max_iterations = options.max_iterations;
        newton_fb_.solve(eq6_, o, r);
      } else {
        EnumerationOptions o;
        o.tolerance = options.tolerance;
        r = enumerate(eq6_, o);
      }
      result.solver_used = solver;
      result.status = r.status;
      result.iterations = r.iterations;
      if (r.z.size() == n) {
        read_eq6_into(fp, r.z.data(), result);
      } else {
        const Vector zero = Vector::Zero(n);
        read_eq6_into(fp, zero.data(), result);
        result.residual = std::numeric_limits<double>::infinity();
      }
      break;
    }
  }
}

FrictionalResult FrictionalSolver::solve(const FrictionalProblem& fp, Solver solver,
                                         const SolveOptions& options) {
  FrictionalResult r;
  solve(fp, solver, options, r);
  return r;
}

FrictionalResult solve_frictional(const FrictionalProblem& fp, Solver solver,
                                  const SolveOptions& options) {
  FrictionalSolver s(fp.contacts());
  return s.solve(fp, solver, options);
}

}  // namespace nsb::lcp
