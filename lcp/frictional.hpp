// The planar frictional contact problem at velocity (impact) or acceleration level, and
// its LCP form, eq. (6) of Shi & Dimitrakopoulos (2017).
//
// For m contacts with normal and tangential directions W_N, W_T (n x m each) and an
// effective inverse mass A^-1 (M^-1 for an impact; the Moreau–Jean iteration matrix inverse
// in a time step), the contact velocities after the impulses Lambda are
//
//   gdot_N+ = G_NN Lambda_N + G_NT Lambda_T + gdot_N,free
//   gdot_T+ = G_TN Lambda_N + G_TT Lambda_T + gdot_T,free            G_XY = W_X^T A^-1 W_Y  (8)
//
// subject to Newton's impact law and Coulomb's law per contact i:
//   gdot_N0,i = gdot_N+,i + eps_i gdot_N-,i >= 0,  Lambda_N,i >= 0,  complementary    (3), (7)
//   |Lambda_T,i| <= mu_i Lambda_N,i,  and  gdot_T+,i != 0  =>  Lambda_T,i = -mu_i Lambda_N,i sgn(gdot_T+,i)
//
// For an impact gdot_free = gdot- (the pre-impact velocities). At acceleration level the
// same form holds with accelerations in place of velocities and eps = 0.
//
// Sign convention of the tangential impulse: Lambda_T acts along +W_T on the body, so a
// body sliding with gdot_T > 0 receives Lambda_T = -mu Lambda_N.
#pragma once

#include "lcp/lcp.hpp"
#include "lcp/lemke.hpp"
#include "lcp/newton_fb.hpp"
#include "lcp/pgs.hpp"
#include "lcp/solve.hpp"

#include <vector>

namespace nsb::lcp {

struct FrictionalProblem {
  // The Delassus matrix G = [G_NN G_NT; G_TN G_TT], 2m x 2m, ordered normals first.
  // When every mu_i = 0 it may instead be m x m (G_NN only): no tangential unknowns.
  Matrix delassus;
  Vector gdot_free;    // [gdot_N,free; gdot_T,free], size 2m (or m when frictionless)
  Vector gdot_n_minus; // pre-impact normal velocities for the restitution law, size m
  Vector restitution;  // eps_i in [0, 1], size m
  Vector friction;     // mu_i >= 0, size m

  Eigen::Index contacts() const { return restitution.size(); }
  bool frictionless() const { return delassus.rows() == contacts(); }
  void validate() const;  // throws std::invalid_argument naming the field and the entry
};

struct FrictionalResult {
  Vector lambda_n;      // Lambda_N, size m
  Vector lambda_t;      // Lambda_T, size m (zeros when frictionless)
  Vector gdot_n_plus;   // post-impact normal velocities
  Vector gdot_t_plus;   // post-impact tangential velocities
  Status status = Status::kNotRun;
  Solver solver_used = Solver::kLemke;  // the solver that produced the answer
  int iterations = 0;
  double residual = std::numeric_limits<double>::infinity();  // see frictional_residual
  bool ok() const { return status == Status::kSolved; }
};

// Eq. (6): the LCP of size 3m in the unknowns (Lambda_N, Lambda_TR, gdot_TL+) with
//   Lambda_TR = mu Lambda_N + Lambda_T,  Lambda_TL = mu Lambda_N - Lambda_T,
//   gdot_TR+ = (|gdot_T+| + gdot_T+)/2,  gdot_TL+ = (|gdot_T+| - gdot_T+)/2   (eq. 4, corrected)
// For a frictionless problem the LCP is of size m: G_NN Lambda_N + gdot_N,free + eps gdot_N-.
//
//        | G_NN - G_NT mu   G_NT   0 |        | gdot_N,free + eps gdot_N- |
//   M =  | G_TN - G_TT mu   G_TT   E |,   q = | gdot_T,free               |
//        | 2 mu             -E     0 |        | 0                         |
//
// (mu = diag(mu_i), E = identity; with gdot_free = gdot- this is the paper's eq. 6.)
// When every mu_i = 0 the tangential unknowns are dropped even if the Delassus matrix is
// 2m x 2m ("frictionless" below means: all mu_i = 0 or the Delassus matrix is m x m).
Problem build_eq6(const FrictionalProblem& fp);
// Size of the LCP build_eq6 returns: m when frictionless in the sense above, else 3m.
Eigen::Index eq6_size(const FrictionalProblem& fp);

// Turns the solution z of build_eq6(fp) (size eq6_size(fp)) back into impulses and post-impact velocities.
FrictionalResult read_eq6(const FrictionalProblem& fp, const Vector& z);

// Residual of the frictional problem, independent of its LCP form: the largest violation of
// the normal complementarity (natural map), of the friction cone, and of the maximum
// dissipation (sliding opposite to the friction impulse), scaled by (1 + ||gdot_free||_inf).
double frictional_residual(const FrictionalProblem& fp, const Vector& lambda_n,
                           const Vector& lambda_t);

// Solves fp with the chosen solver only: Lemke, Newton–FB and enumeration on eq. (6); PGS on
// the natural form (normal impulses in [0, inf), tangential in [-mu Lambda_N, mu Lambda_N]).
// A solver that fails says so in the status; trying another one is the caller's policy (the
// contact stage's fallback chain, integrators/contact_stage.hpp). When Lemke ends on a
// secondary ray or reports round-off (kRayTermination, kRoundOff), it is retried on eq. (6) with
// a diagonal shift of 1e-14 to 1e-12 (relative to the diagonal); such an answer is accepted
// only if it solves the unshifted LCP to options.tolerance. This handles a body wedged
// between contacts whose impulses can balance each other, where the solution set is
// unbounded and round-off otherwise ends the pivoting path on a ray.
FrictionalResult solve_frictional(const FrictionalProblem& fp, Solver solver,
                                  const SolveOptions& options = {});

// PGS on the natural form (no LCP of eq. 6): one sweep visits the contacts in order and sets
//   Lambda_N,i <- max(0, Lambda_N,i - omega gdot_N0,i / G_NN,ii)
//   Lambda_T,i <- clamp(Lambda_T,i - omega gdot_T+,i / G_TT,ii, -mu_i Lambda_N,i, mu_i Lambda_N,i)
// with gdot_N0 = gdot_N+ + eps gdot_N- (eqs. 3 and 7) evaluated with the newest impulses.
// A G_NN,ii <= 0 (or G_TT,ii <= 0 with mu_i > 0) gives kZeroDiagonal. It stops when
// frictional_residual <= options.tolerance. The start is (lambda_n0, lambda_t0) when their
// sizes are m, else zero. options.max_iterations (sweeps) and options.relaxation apply.
FrictionalResult pgs_frictional(const FrictionalProblem& fp, const PgsOptions& options,
                                const Vector& lambda_n0 = {}, const Vector& lambda_t0 = {});

// The same computations as solve_frictional with workspaces kept between calls, for the
// integrators that solve one contact problem per step. After reserve(m) (or a first call with
// m contacts), a call with at most m contacts allocates nothing for Lemke and PGS apart from
// resizing the result's vectors, which Eigen does only when the contact count changes.
// Newton–FB keeps its LCP and result between calls (allocation-free for m <= 4 once sized);
// enumeration allocates (it is an oracle, not meant for the time-stepping hot path).
class FrictionalSolver {
 public:
  explicit FrictionalSolver(Eigen::Index max_contacts = 0);
  void reserve(Eigen::Index contacts);
  // Same semantics and result as solve_frictional(fp, solver, options).
  void solve(const FrictionalProblem& fp, Solver solver, const SolveOptions& options,
             FrictionalResult& result);
  FrictionalResult solve(const FrictionalProblem& fp, Solver solver,
                         const SolveOptions& options = {});

 private:
  void assemble(const FrictionalProblem& fp, Eigen::Index n);
  void run_lemke(const FrictionalProblem& fp, const SolveOptions& options,
                 FrictionalResult& result);
  Eigen::Index capacity_ = 0;
  std::vector<double> matrix_;  // eq. (6) M, column-major, up to (3m)^2
  std::vector<double> q_;
  std::vector<double> z_;
  std::vector<double> lambda_;  // PGS: [Lambda_N; Lambda_T]
  Lemke lemke_;
  NewtonFb newton_fb_;
  Problem eq6_;                 // Newton–FB: the LCP of eq. (6)
  Result eq6_result_;
};

}  // namespace nsb::lcp
