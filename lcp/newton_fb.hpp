// Semismooth Newton method on the Fischer–Burmeister reformulation of the LCP
// (De Luca, Facchinei & Kanzow 1996; Facchinei & Pang 2003, §9.1).
//
//   phi(a, b) = sqrt(a^2 + b^2) - a - b,     phi(a, b) = 0  <=>  a >= 0, b >= 0, a b = 0,
//   Phi_i(z) = phi(z_i, w_i),  w = M z + q,   Psi(z) = 1/2 ||Phi(z)||^2 (smooth merit).
//
// Generalised Jacobian element H = D_a + D_b M with diagonal D_a, D_b:
//   (z_i, w_i) != (0, 0):  D_a,ii = z_i / r_i - 1,  D_b,ii = w_i / r_i - 1,  r_i = ||(z_i, w_i)||;
//   (z_i, w_i)  = (0, 0):  D_a,ii = c_i / s_i - 1,  D_b,ii = (M c)_i / s_i - 1,
//                          s_i = ||(c_i, (M c)_i)||, with c the indicator of the degenerate set
//   (De Luca, Facchinei & Kanzow 1996, Procedure 2.1; the limit along z + t c, t -> 0+).
// The step solves H d = -Phi. If H is singular or d is not a sufficient descent direction
// for Psi, the step is d = -grad Psi = -H^T Phi. Sufficient descent is the angle test
// grad Psi^T d <= -c ||grad Psi|| ||d||: it is invariant to the scale of the data, unlike the
// test -rho ||d||^p of De Luca et al., which rejects good Newton steps of ill-conditioned
// problems (there ||d|| stays O(1) while Psi is already tiny). For an exact Newton step
// grad^T d = -||Phi||^2, so the test only rejects steps from an H with cond(H) > 1/c. An Armijo
// backtracking search on Psi then fixes the step length. A row with D_b,ii = 0 (z_i = 0 and
// w_i > 0 exactly, the inactive components of z = 0 and of every active-set point) reads
// D_a,ii d_i = -Phi_i = 0, so the linear solve runs only on the other rows: the same direction
// from an LU of their block. Singularity is judged on that block (reciprocal condition estimate
// below 1e-14, computed when the LU's pivots spread over more than 1e8). On nondegenerate
// problems with a P-matrix, the unit step is accepted near the solution and convergence is
// quadratic.
//
// Active-set steps (option `polish`): after each damped step, the support estimates
// A = {i : z_i > w_i} of the new iterate and of the full (undamped) Newton point give trial
// points z_A = max(0, -M_AA^-1 q_A), z_rest = 0 (the exact solution if A is the true support;
// identification of the active set, Facchinei, Fischer & Kanzow 1998; a singular M_AA is
// solved in the least-norm sense). A trial is taken as the next iterate if it lowers Psi, so
// the iteration stays monotone in Psi and keeps the global behaviour of the damped Newton
// method, while the slow middle phase of ill-conditioned problems, where Armijo steps crawl
// although the support is already known, is cut short. A set already tried is not re-solved.
#pragma once

#include "lcp/lcp.hpp"

#include <memory>

namespace nsb::lcp {

struct NewtonFbOptions {
  double tolerance = 1e-12;     // kSolved when lcp::residual <= tolerance; > 0
  int max_iterations = 100;     // Newton step limit; >= 1
  double armijo = 1e-4;         // sufficient decrease factor sigma; in (0, 0.5)
  double backtrack = 0.5;       // step length reduction per trial; in (0, 1)
  int max_backtracks = 60;      // trials before the line search fails; >= 1
  double descent_angle = 1e-12; // c of the angle test above; in (0, 1)
  bool record_history = false;  // lcp::residual after every step into Result::history
  bool polish = true;           // try the active-set solution (see above)
  void validate() const;        // throws std::invalid_argument naming the field
};

// A reusable Newton–FB solver: problems with n <= kSmall use a workspace inside the call
// (no heap), larger ones a workspace kept between calls. solve() fills r without clock or
// message; r's vectors are resized only when n changes.
class NewtonFb {
 public:
  static constexpr int kSmall = 12;  // the largest eq. (6) problem of the bridge (4 contacts)
  NewtonFb();
  ~NewtonFb();
  NewtonFb(NewtonFb&&) noexcept;
  NewtonFb& operator=(NewtonFb&&) noexcept;
  // Starts from warm_start if its size is n, otherwise from z = 0.
  void solve(const Problem& p, const NewtonFbOptions& options, Result& r,
             const Vector& warm_start = {});

 private:
  struct Large;
  std::unique_ptr<Large> large_;
};

// Solves p starting from warm_start (if its size is n; otherwise from z = 0), with the wall
// time and Result::message.
Result newton_fb(const Problem& p, const NewtonFbOptions& options = {},
                 const Vector& warm_start = {});

// Phi(z) and the Jacobian element H described above (exposed for the finite-difference test).
void fischer_burmeister(const Problem& p, const Vector& z, Vector& phi, Matrix& H);

}  // namespace nsb::lcp
