// Manufactured LCPs over the matrix classes of the solvers' theory: choose z* and w* with
// complementary supports, a matrix, and q = w* - M z*. Every solver must return z* where the
// solution is unique (P-matrices), a valid solution with the unique w* where only w is unique
// (symmetric PSD), and a failure status where no solution exists. Plus eq. (6) problems from
// random planar rigid bodies, every solver against enumeration.
#include "lcp/enumeration.hpp"
#include "lcp/frictional.hpp"
#include "lcp/lemke.hpp"
#include "lcp/newton_fb.hpp"
#include "lcp/pgs.hpp"
#include "lcp/solve.hpp"
#include "lcp/test/problems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace nsb::lcp;
using testing::lcp_violations;
using testing::relative_distance;

namespace {
// The LCP conditions on z and w directly, relative to 1 + ||q||_inf; the solvers stop at
// 1e-12 on the same scale.
constexpr double kConditions = 1e-10;
// Forward error of z against z*: the backward error (1e-12) times cond(M), with a factor
// 10 for the size of the data.
double forward(double cond) { return std::max(1e-10, 10.0 * cond * 1e-12); }
}  // namespace

TEST_CASE("SPD with condition numbers up to 1e8: Lemke, Newton-FB (and PGS up to 1e3)") {
  std::mt19937 rng(20170615);
  int pgs_runs = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const int n = 2 + (trial * 7) % 59;
    const double cond = std::pow(10.0, trial % 9);
    const double scale = std::pow(10.0, (trial % 7) - 3);
    const auto m = testing::manufacture(rng, testing::spd(rng, n, cond, scale),
                                        trial % 3 == 0 ? 0.2 : 0.0, 1.0);
    for (Solver s : {Solver::kLemke, Solver::kNewtonFb, Solver::kPgs}) {
      if (s == Solver::kPgs && cond > 1e3) continue;  // linear rate 1 - O(1/cond)
      SolveOptions o;
      if (s == Solver::kPgs) o.max_iterations = 200000;
      const Result r = solve(m.problem, s, o);
      INFO("trial " << trial << ", n = " << n << ", cond = " << cond << ", scale = " << scale
                    << ", solver " << to_string(s) << ": " << to_string(r.status));
      REQUIRE(r.ok());
      pgs_runs += s == Solver::kPgs;
      CHECK(lcp_violations(m.problem, r.z, kConditions).empty());
      // z* is O(1) and M is O(scale): the forward error grows with cond / scale.
      CHECK(relative_distance(r.z, m.z) <= forward(cond) / std::min(1.0, scale));
    }
  }
  CHECK(pgs_runs > 40);
}

TEST_CASE("nonsymmetric P-matrices: the unique solution, by Lemke, Newton-FB and enumeration") {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 1 + (trial * 5) % 40;
    const auto m = testing::manufacture(rng, testing::p_matrix(rng, n, 1.0 + trial % 50),
                                        trial % 4 == 0 ? 0.3 : 0.0);
    for (Solver s : {Solver::kLemke, Solver::kNewtonFb, Solver::kEnumeration}) {
      if (s == Solver::kEnumeration && n > 10) continue;
      const Result r = solve(m.problem, s);
      INFO("trial " << trial << ", n = " << n << ", solver " << to_string(s));
      REQUIRE(r.ok());
      CHECK(relative_distance(r.z, m.z) < 1e-8);
    }
  }
}

TEST_CASE("singular PSD: a valid solution and the unique w") {
  // Symmetric PSD: any two solutions have the same w (Cottle, Pang & Stone, Thm 3.1.7).
  std::mt19937 rng(9);
  int nfb_solved = 0;
  int nfb_runs = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 3 + trial % 30;
    const int rank = 1 + trial % (n - 1);
    const auto m = testing::manufacture(rng, testing::singular_psd(rng, n, rank), 0.2);
    for (Solver s : {Solver::kLemke, Solver::kPgs, Solver::kNewtonFb, Solver::kEnumeration}) {
      if (s == Solver::kEnumeration && n > 10) continue;
      SolveOptions o;
      if (s != Solver::kLemke && s != Solver::kEnumeration) {
        o.tolerance = 1e-10;  // both converge linearly at a non-isolated solution
        o.max_iterations = s == Solver::kPgs ? 200000 : 500;
      }
      const Result r = solve(m.problem, s, o);
      INFO("trial " << trial << ", n = " << n << ", rank " << rank << ", solver "
                    << to_string(s) << ": " << to_string(r.status));
      if (s == Solver::kNewtonFb) {
        ++nfb_runs;
        // The FB Jacobian is singular at a non-isolated solution; the method may stall.
        if (!r.ok()) continue;
        ++nfb_solved;
      }
      REQUIRE(r.ok());
      CHECK(lcp_violations(m.problem, r.z, 1e-8).empty());
      CHECK(relative_distance(r.w, m.w) < 1e-6);
    }
  }
  MESSAGE("Newton-FB solved " << nfb_solved << " of " << nfb_runs << " singular PSD problems");
  CHECK(nfb_solved * 2 > nfb_runs);
}

TEST_CASE("problems without a solution end with the right status") {
  // M = -I, q = -e: w = -z - e < 0 for all z >= 0.
  Problem p;
  p.M = -Matrix::Identity(4, 4);
  p.q = -Vector::Ones(4);
  CHECK(solve(p, Solver::kLemke).status == Status::kRayTermination);
  CHECK(solve(p, Solver::kPgs).status == Status::kZeroDiagonal);
  CHECK_FALSE(solve(p, Solver::kNewtonFb).ok());
  CHECK(solve(p, Solver::kEnumeration).status == Status::kNoSolution);
  // Random infeasible problems: a row i with M_i. <= 0 and q_i < 0 makes w_i < 0 for every
  // z >= 0 (Farkas certificate y = e_i). The rest of M is a P-matrix.
  std::mt19937 rng(13);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 2 + trial % 9;
    Problem q;
    q.M = testing::p_matrix(rng, n);
    q.q = testing::random_vector(rng, n);
    const int i = trial % n;
    q.M.row(i) = -testing::random_vector(rng, n, 0.0, 1.0).transpose();
    q.q(i) = -0.5;
    INFO("trial " << trial);
    CHECK(solve(q, Solver::kLemke).status == Status::kRayTermination);
    CHECK(solve(q, Solver::kEnumeration).status == Status::kNoSolution);
    CHECK_FALSE(solve(q, Solver::kNewtonFb).ok());
    CHECK_FALSE(solve(q, Solver::kPgs).ok());
  }
}

TEST_CASE("eq. 6 from random planar rigid bodies: all solvers against enumeration") {
  std::mt19937 rng(1234);
  int compared = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int contacts = 1 + trial % 4;
    // eps > 0 only where a solution is guaranteed (see lcp/test/frictional_test.cpp).
    const double eps = contacts <= 2 ? 0.25 * (trial % 3) : 0.0;
    const double mu = 0.25 * (trial % 4);
    const auto b = testing::rigid_body_impact(rng, contacts, eps, mu);
    const Problem p = build_eq6(b.problem);
    const Result e = enumerate(p);
    INFO("trial " << trial << ", " << contacts << " contacts, eps " << eps << ", mu " << mu);
    REQUIRE(e.ok());
    for (Solver s : {Solver::kLemke, Solver::kPgs, Solver::kNewtonFb}) {
      const FrictionalResult r = solve_frictional(b.problem, s);
      INFO("solver " << to_string(s) << ": " << to_string(r.status));
      if (s == Solver::kLemke) REQUIRE(r.ok());
      if (!r.ok()) continue;
      CHECK(r.residual < 1e-10);
      // Newton's and Coulomb's laws through the independent residual of the impulses.
      CHECK(frictional_residual(b.problem, r.lambda_n, r.lambda_t) < 1e-10);
      // With one contact or a frictionless full-rank problem the impulses are unique.
      const bool unique = contacts == 1 || (mu == 0.0 && contacts <= 3);
      if (unique) {
        const FrictionalResult ref = read_eq6(b.problem, e.z);
        CHECK((r.lambda_n - ref.lambda_n).lpNorm<Eigen::Infinity>() <
              1e-8 * (1.0 + ref.lambda_n.lpNorm<Eigen::Infinity>()));
        ++compared;
      }
    }
  }
  CHECK(compared > 200);
}
