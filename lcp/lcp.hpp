// The linear complementarity problem and what every solver returns.
//
//   Find z in R^n with   z >= 0,   w = M z + q >= 0,   z^T w = 0.     (Cottle, Pang & Stone 1992)
//
// One problem type and one result type are shared by every solver (Lemke, PGS, Newton–FB,
// enumeration), so that tests, benchmarks and the command line loop over solvers.
#pragma once

#include <Eigen/Dense>

#include <chrono>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace nsb::lcp {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// An LCP(M, q). M is square, q has the same size; n = 0 is a valid (trivial) problem.
struct Problem {
  Matrix M;
  Vector q;

  Eigen::Index size() const { return q.size(); }
  // Throws std::invalid_argument if M is not n x n with n = q.size(), or if any entry is
  // NaN or infinite. Names the offending entry.
  void validate() const;
};

// The outcome of a solve. Each value says whether z is usable.
enum class Status {
  kNotRun,           // default: the solver never ran; z is empty.
  kSolved,           // residual <= tolerance; z is a solution.
  kMaxIterations,    // iteration or pivot limit reached; z is the last iterate, not a solution.
  kRayTermination,   // Lemke: secondary ray, no solution found (none exists or M is not
                     // in a class Lemke processes): the entering column has no positive
                     // entry at all; z is not usable.
  kRoundOff,         // Lemke: round-off lost the pivoting path: the path stopped on a ray
                     // that does not verify on the original data (the basic point or the ray
                     // direction violates w - M z - d z0 = q, or has a negative component, by
                     // more than 1e-9 relative), or z0 left the basis but the residual stays
                     // above the tolerance after the refinement. z is the last basic solution,
                     // not usable; a slightly perturbed problem or another solver may succeed.
  kZeroDiagonal,     // PGS: a diagonal entry of M is <= 0; z is not usable.
  kSingularJacobian, // Newton–FB: the linear system of a Newton step is singular and the
                     // gradient step made no progress; z is the last iterate.
  kLineSearchFailed, // Newton–FB: no descent on 1/2 ||Phi||^2 possible; z is the last iterate.
  kNoSolution,       // Enumeration: no complementary basis solves the problem; z is empty.
  kTooLarge,         // Enumeration: n exceeds the enumeration limit; nothing was done.
};

std::string_view to_string(Status s);
// A one-sentence description of what the status means for z, for messages. Solvers do not
// build messages on their hot path; the by-value solve functions fill Result::message from
// this (and add the detail they know, e.g. which diagonal entry is not positive).
std::string_view describe(Status s);

// One result type for every LCP solver, returned by value. Defaults mean "never ran".
struct Result {
  Vector z;                                   // the solution (or last iterate), size n
  Vector w;                                   // M z + q
  Status status = Status::kNotRun;
  int iterations = 0;                         // sweeps, Newton steps or pivots
  double residual = std::numeric_limits<double>::infinity();       // see lcp::residual
  double siconos_error = std::numeric_limits<double>::infinity();  // see lcp::siconos_error
  double wall_time = 0.0;                     // seconds spent in the solver; measured only
                                              // by the by-value solve functions, 0 otherwise
  std::string message;                        // a human-readable note on the outcome; filled
                                              // only by the by-value solve functions
  std::vector<double> history;                // residual per iteration, when requested
  bool ok() const { return status == Status::kSolved; }
};

// The residual every solver stops on and every test checks, with w = M z + q:
//
//   r(z) = || min(z, w) ||_inf / (1 + ||q||_inf)
//
// min(z, w) = 0 componentwise is equivalent to the three LCP conditions (the natural map,
// Facchinei & Pang 2003, §1.5). The denominator makes the measure relative for large data
// and absolute near q = 0.
double residual(const Matrix& M, const Vector& q, const Vector& z);

// Siconos Numerics' error measure (lcp_compute_error), for one-to-one comparison:
//
//   e(z) = || z - max(0, z - w) ||_2 / ||q||_2     (divided by 1 when ||q||_2 = 0)
double siconos_error(const Matrix& M, const Vector& q, const Vector& z);

// Fills r.w, r.residual and r.siconos_error from r.z: one product w = M z + q, then both
// measures in one pass over (z, w). No allocation when r.w already has size n.
void evaluate(const Problem& p, Result& r);
// The same when r.w already holds M z + q (a solver that computed it): both measures in one
// pass, no product.
void evaluate_measures(const Problem& p, Result& r);

// The wall clock of a by-value solve: started at construction, read by finish(), which sets
// the status, the message (describe(s) unless one is given) and the wall time. The in-place
// solvers (Lemke::solve(p, o, r), pgs(p, o, r), NewtonFb::solve) never read the clock.
class SolveClock {
 public:
  SolveClock();
  Result& finish(Result& r) const;                       // message = describe(r.status)
  Result& finish(Result& r, std::string message) const;  // a message with more detail

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace nsb::lcp
