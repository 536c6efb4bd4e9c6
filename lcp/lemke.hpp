// Lemke's complementary pivoting method with a covering vector and a lexicographic ratio test.
//
// The scheme (Cottle, Pang & Stone 1992, §4.4; Murty 1988, ch. 2): augment the LCP with an
// artificial variable z0 and a covering vector d > 0,
//
//   w = M z + d z0 + q,   w, z, z0 >= 0,   w^T z = 0,
//
// start from the almost-complementary basis {w} with z0 = max_i(-q_i / d_i), and pivot in the
// complement of the variable that just left, until z0 leaves (a solution) or the entering
// column has no positive entry (a secondary ray: no solution found).
//
// Round-off is told apart from a ray (Status::kRoundOff). A ray termination is reported only
// if the basic point and the ray direction, read from the tableau, satisfy w - M z - d z0 = q
// (and = 0 for the direction) with nonnegative components on the original data to a relative
// 1e-9; otherwise the tableau has lost the path to round-off (tiny pivots that spoilt it). If
// z0 has reached zero to round-off when the path stops on a ray, z is a solution and is
// reported as one. When z0 leaves the basis but the residual stays above the tolerance even
// after the refinement below, the status is also kRoundOff.
//
// Degeneracy: ties in the ratio test are broken lexicographically on the rows of
// [B^-1 q, B^-1] divided by the pivot column (Cottle, Pang & Stone §4.9). This is the
// perturbation q + (eps, eps^2, ..., eps^n), so no basis repeats and the method cannot cycle.
//
// The tableau B^-1 [I, -M, -d, q] lives in a workspace sized once: a pivot does no heap
// allocation. A final refinement re-solves M_BB z_B = -q_B on the original data when the
// tableau's round-off leaves the residual above the tolerance. For n <= 12 the pivoting runs
// with n known at compile time (lcp/fixed_size.hpp), the same arithmetic with unrolled loops.
#pragma once

#include "lcp/lcp.hpp"

#include <vector>

namespace nsb::lcp {

struct LemkeOptions {
  double tolerance = 1e-12;        // kSolved when lcp::residual <= tolerance; > 0
  int max_pivots = 0;              // pivot limit; 0 selects default_max_pivots(n); >= 0
  double pivot_tolerance = 1e-12;  // an entry of the entering column counts as positive if it
                                   // exceeds pivot_tolerance * ||column||_inf; in (0, 1e-3]
  Vector covering;                 // d > 0, size n; empty selects d = (1, ..., 1)
  void validate() const;           // throws std::invalid_argument naming the field
  static int default_max_pivots(Eigen::Index n);
};

// A reusable Lemke solver. After reserve(n) (or a first solve of size n), solving problems of
// size <= n allocates nothing except what a returned Result itself holds.
class Lemke {
 public:
  explicit Lemke(Eigen::Index capacity = 0);
  void reserve(Eigen::Index n);
  Eigen::Index capacity() const { return capacity_; }

  // The allocation-free core: writes the solution (or last iterate) into z (size n) and
  // returns the status; pivots() and last_residual() describe the run. Throws
  // std::invalid_argument if M is not n x n or z not of size n (n = q.size()); the data are
  // not otherwise validated here (Lemke::solve does that).
  Status run(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
             const LemkeOptions& options, Eigen::Ref<Vector> z);
  int pivots() const { return pivots_; }
  double last_residual() const { return residual_; }
  // M z + q of the last run (size n), computed once for the residual.
  const double* last_w() const { return w_.data(); }

  // The shared result type without clock or message: validates p and the options, then
  // fills r.z, r.w, both residuals, the status and the pivot count. r's vectors are resized
  // only when n changes, so a reused Result makes this allocation-free.
  void solve(const Problem& p, const LemkeOptions& options, Result& r);
  // The same into a new Result, with the wall time and Result::message (describe(status)).
  Result solve(const Problem& p, const LemkeOptions& options = {});

 private:
  // The members below taking N run with n = N known at compile time (N > 0, see
  // lcp/fixed_size.hpp) or n = n_ (N = Eigen::Dynamic); the arithmetic is the same.
  template <int N>
  Status run_n(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
               const LemkeOptions& options, Eigen::Ref<Vector> z);
  template <int N>
  void solve_n(const Problem& p, const LemkeOptions& options, Result& r);
  template <int N>
  void load_tableau(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                    const LemkeOptions& options);
  template <int N>
  Status complementary_pivots(int limit, Eigen::Index& entering);
  template <int N>
  Status read_solution(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                       const LemkeOptions& options, Status status, Eigen::Index entering,
                       Eigen::Ref<Vector> z);
  template <int N>
  void pivot(Eigen::Index row, Eigen::Index entering);
  // The first pivot (z0 entering) ranks the rows differently from every later one.
  enum class PivotKind { kFirst, kLater };
  // Leaving row for the entering variable; -1: no entry above the pivot tolerance.
  template <int N>
  Eigen::Index ratio_test(Eigen::Index entering, PivotKind kind);
  void check(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
             Eigen::Index z_size) const;
  bool ray_verified(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                    const LemkeOptions& options, Eigen::Index entering);
  template <int N>
  double natural_residual(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
                          const Eigen::Ref<const Vector>& z);
  bool refine(const Eigen::Ref<const Matrix>& M, const Eigen::Ref<const Vector>& q,
              Eigen::Ref<Vector> z);

  Eigen::Index capacity_ = 0;
  Eigen::Index n_ = 0;
  std::vector<double> tableau_;   // n x (2n + 2), column-major: w | z | z0 | q
  std::vector<double> column_;    // copy of the entering column
  std::vector<double> ratio_;     // the ratio test's ratios
  std::vector<double> lu_;        // k x k for the refinement
  std::vector<double> rhs_;
  std::vector<double> w_;         // M z + q of the last run
  std::vector<Eigen::Index> basis_;     // basic variable of each row
  std::vector<Eigen::Index> position_;  // row of each variable, -1 when non-basic
  std::vector<Eigen::Index> candidates_;
  std::vector<Eigen::Index> index_;
  int pivots_ = 0;
  double residual_ = 0.0;
  double pivot_tolerance_ = 1e-12;
};

// Free-function form for one-off solves.
Result lemke(const Problem& p, const LemkeOptions& options = {});

}  // namespace nsb::lcp
