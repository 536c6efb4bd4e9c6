// Lemke's method: hand-solved problems, degeneracy, ray termination, Murty's exponential
// example, the pivot limit, workspace reuse and the edges.
#include "lcp/enumeration.hpp"
#include "lcp/frictional.hpp"
#include "lcp/lemke.hpp"
#include "lcp/test/problems.hpp"

#include <doctest/doctest.h>

#include <limits>
#include <random>
#include <stdexcept>
#include <string>

using namespace nsb::lcp;
using nsb::lcp::testing::lcp_violations;
using nsb::lcp::testing::relative_distance;

namespace {
// Hand solutions are rationals; a handful of pivots loses at most a few ulps.
constexpr double kHand = 1e-14;

Problem make(const Matrix& M, const Vector& q) {
  Problem p;
  p.M = M;
  p.q = q;
  return p;
}

// Murty (1988), ch. 6: M upper triangular with ones on the diagonal and 2 above it,
// q_i = -(2^(n+1) - 2^i), i = 1..n. These are the data of data/siconos-lcp/lcp_exp_murty2.dat
// for n = 6.
Problem murty(int n) {
  Problem p;
  p.M = Matrix::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) p.M(i, j) = 2.0;
  p.q.resize(n);
  for (int i = 1; i <= n; ++i) p.q(i - 1) = -(std::ldexp(1.0, n + 1) - std::ldexp(1.0, i));
  return p;
}

// Two eq. (6) problems of a deck wedged between two abutments (2 contacts with opposite
// normals at both ends, lever arms 1e-2 apart, mu = 0.5, eps = 0): G = W^T M^-1 W has rank 3 of
// 4, and the impulses of the two ends nearly balance, so the pivoting path runs through
// near-ties. Data printed exactly (hexadecimal) from the generator that found them.
Problem wedged_deck(bool second) {
  Problem p;
  p.M.resize(6, 6);
  if (!second) {
    p.M << 0x1.9244e085ff996p-1, -0x1.926c93c32d582p-1, 0x1.3d9899d31604cp-12, 0x1.3d9899d31604cp-12, 0, 0,
        -0x1.92426485c22d3p-1, 0x1.926f101c91f6p-1, -0x1.655b3cdf994b3p-12, -0x1.655b3cdf994b3p-12, 0, 0,
        -0x1.9185dd20ac383p+0, -0x1.91075ffba9811p-1, 0x1.9199b6aa49699p+1, 0x1.90dab4940d8dep+0, 1, 0,
        -0x1.90b30180d32b2p-1, -0x1.91b00c5e17632p+0, 0x1.90dab4940d8dep+0, 0x1.9199b6aa49699p+1, 0, 1,
        1, 0, -1, 0, 0, 0,
        0, 1, 0, -1, 0, 0;
    p.q.resize(6);
    p.q << -0x1.d67a0189c48dap-2, 0x1.d67a76da88dd9p-2, -0x1.bd7a9e2fe9608p-2, 0x1.bee083d726f19p-3, 0, 0;
  } else {
    p.M << 0x1.261267ad88e27p-1, -0x1.26219ceb38584p-1, 0x1.e6c255049a0eep-14, 0x1.e6c255049a0eep-14, 0, 0,
        -0x1.262a7e6d12edp-1, 0x1.260987245cc8bp-1, 0x1.07c8b2ea7285fp-12, 0x1.07c8b2ea7285fp-12, 0, 0,
        -0x1.25c06962bf7dcp+0, -0x1.25550d4e28701p-1, 0x1.25c8046c13903p+1, 0x1.2576066485be6p+0, 1, 0,
        -0x1.2566d051dd999p-1, -0x1.25b787e0e4e9p+0, 0x1.2576066485be6p+0, 0x1.25c8046c13903p+1, 0, 1,
        1, 0, -1, 0, 0, 0,
        0, 1, 0, -1, 0, 0;
    p.q.resize(6);
    p.q << 0x1.2d059f7f6836ap-3, -0x1.2d3ba6bb3d458p-3, -0x1.963d1dcd29a24p-3, -0x1.886137b79f447p-1, 0, 0;
  }
  return p;
}
}  // namespace

TEST_CASE("hand-solved: 2 x 2 with both components positive") {
  // M = [2 1; 1 2], q = (-5, -6). Guess w = 0: 2 z1 + z2 = 5, z1 + 2 z2 = 6
  // => z1 = 4/3, z2 = 7/3, both > 0, so z = (4/3, 7/3), w = 0 is the (unique, M is P) solution.
  const Problem p = make((Matrix(2, 2) << 2, 1, 1, 2).finished(), (Vector(2) << -5, -6).finished());
  const Result r = lemke(p);
  REQUIRE(r.status == Status::kSolved);
  CHECK(r.z(0) == doctest::Approx(4.0 / 3.0).epsilon(kHand));
  CHECK(r.z(1) == doctest::Approx(7.0 / 3.0).epsilon(kHand));
  CHECK(r.w.lpNorm<Eigen::Infinity>() < kHand * 10);
  CHECK(r.residual <= LemkeOptions{}.tolerance);
}

TEST_CASE("hand-solved: mixed support") {
  // M = I, q = (-1, 2): w = z + q, so z1 = 1 (w1 = 0) and z2 = 0 (w2 = 2).
  const Problem p = make(Matrix::Identity(2, 2), (Vector(2) << -1, 2).finished());
  const Result r = lemke(p);
  REQUIRE(r.ok());
  CHECK(r.z(0) == doctest::Approx(1.0).epsilon(kHand));
  CHECK(r.z(1) == 0.0);
  CHECK(r.w(1) == doctest::Approx(2.0).epsilon(kHand));
}

TEST_CASE("degenerate ties: the lexicographic rule terminates at the solution") {
  // M = [1 2 0; 0 1 2; 2 0 1], q = -e. Every ratio of the first pivot ties. M is a P-matrix
  // (principal minors 1, 1, 1, 1 and det M = 1 + 2*4 = 9), so the solution is unique; by the
  // cyclic symmetry it is z = e/3 with M z = (1 + 2)/3 e = e, w = 0.
  const Problem p =
      make((Matrix(3, 3) << 1, 2, 0, 0, 1, 2, 2, 0, 1).finished(), -Vector::Ones(3));
  const Result r = lemke(p);
  REQUIRE(r.ok());
  CHECK(relative_distance(r.z, Vector::Constant(3, 1.0 / 3.0)) < kHand);

  // Fully degenerate manufactured problems: half the indices have z_i = w_i = 0.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const auto m = testing::manufacture(rng, testing::p_matrix(rng, 2 + trial % 9), 0.5);
    const Result s = lemke(m.problem);
    INFO("trial " << trial);
    REQUIRE(s.ok());
    CHECK(relative_distance(s.z, m.z) < 1e-10);
  }
}

TEST_CASE("no solution: M = -I, q = -e ends in ray termination") {
  // w = -z - e < 0 for every z >= 0: infeasible, so no method can succeed.
  const Problem p = make(-Matrix::Identity(3, 3), -Vector::Ones(3));
  const Result r = lemke(p);
  CHECK(r.status == Status::kRayTermination);
  CHECK_FALSE(r.ok());
  CHECK(enumerate(p).status == Status::kNoSolution);
}

TEST_CASE("round-off: a stop with z0 at zero to round-off is a solution, not a ray") {
  // This input used to be reported as kRayTermination, with a z that solves the LCP: z0 had
  // reached zero to round-off when the entering column showed no blocking row. The LCP
  // conditions are checked here from M and q directly.
  const Problem p = wedged_deck(false);
  const Result r = lemke(p);
  CHECK(r.status == Status::kSolved);
  const Vector w = p.M * r.z + p.q;
  const double scale = 1.0 + p.q.lpNorm<Eigen::Infinity>();
  CHECK(r.z.minCoeff() >= 0.0);
  CHECK(w.minCoeff() >= -1e-12 * scale);
  CHECK(r.z.cwiseProduct(w).cwiseAbs().maxCoeff() <= 1e-12 * scale * scale);
}

TEST_CASE("round-off: a lost path has its own status, and the problem has a solution") {
  // z0 leaves the basis (in exact arithmetic z solves the LCP), but the tableau's round-off
  // leaves r = 1.8e-12 > 1e-12 even after the refinement. This input used to be reported as
  // kMaxIterations after 8 of 5000 pivots. Enumeration, an independent method, solves it.
  const Problem p = wedged_deck(true);
  const Result r = lemke(p);
  CHECK(r.status == Status::kRoundOff);
  CHECK(r.iterations < LemkeOptions::default_max_pivots(p.size()));
  CHECK(r.residual > 1e-12);
  CHECK(r.residual < 1e-10);  // measured 1.8e-12: round-off, not a wrong basis
  const Result e = enumerate(p);
  REQUIRE(e.ok());
  CHECK(residual(p.M, p.q, e.z) <= 1e-12);
  CHECK_FALSE(describe(Status::kRoundOff).empty());
}

TEST_CASE("round-off: a ray from a spoilt tableau is not reported as a secondary ray") {
  // Genuine rays verify on the original data (M = -I, CPS_3-like data): each is still
  // kRayTermination. A ray whose basic point or direction violates w - M z - d z0 = q by more
  // than 1e-9 relative is kRoundOff: random wedged bodies with restitution (infeasible, see
  // frictional_test) produce both kinds; both are failures, never kSolved.
  const Problem ray = make(-Matrix::Identity(4, 4), -Vector::Ones(4));
  CHECK(lemke(ray).status == Status::kRayTermination);
  std::mt19937 rng(2017);
  int verified = 0;
  int spoilt = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const auto b = testing::rigid_body_impact(rng, 4, 0.5, 0.5);
    const Problem p = build_eq6(b.problem);
    const Result r = lemke(p);
    if (r.status == Status::kRayTermination) ++verified;
    if (r.status == Status::kRoundOff) ++spoilt;
    if (r.ok()) CHECK(r.residual <= 1e-12);
  }
  CHECK(verified > 0);
  CHECK(spoilt > 0);
}

TEST_CASE("Murty's example needs 2^n pivots") {
  // Murty (1988), ch. 6: the complementary pivot method with covering vector e visits 2^n
  // almost-complementary bases on this family (counting the first pivot, which brings z0
  // in: 2^n - 1 pivots after it). The solution is unique (triangular, unit diagonal: P).
  for (int n = 1; n <= 10; ++n) {
    const Problem p = murty(n);
    const Result r = lemke(p);
    INFO("n = " << n);
    REQUIRE(r.ok());
    CHECK(r.iterations == (1 << n));
    if (n <= 8) {
      const Result e = enumerate(p);
      CHECK(relative_distance(r.z, e.z) < kHand);
    }
  }
}

TEST_CASE("pivot limit: max_pivots = 1 gives kMaxIterations") {
  const Problem p = make((Matrix(2, 2) << 2, 1, 1, 2).finished(), (Vector(2) << -5, -6).finished());
  LemkeOptions o;
  o.max_pivots = 1;
  const Result r = lemke(p, o);
  CHECK(r.status == Status::kMaxIterations);
  CHECK(r.iterations == 1);
}

TEST_CASE("edges: n = 0, q >= 0, NaN input, bad options") {
  Problem empty;
  const Result r0 = lemke(empty);
  CHECK(r0.ok());
  CHECK(r0.z.size() == 0);

  // q >= 0: z = 0, w = q solves it without a pivot.
  const Problem pos = make(-Matrix::Identity(2, 2), (Vector(2) << 0, 3).finished());
  const Result r1 = lemke(pos);
  CHECK(r1.ok());
  CHECK(r1.iterations == 0);
  CHECK(r1.z.isZero(0.0));

  Problem nan = pos;
  nan.M(0, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(lemke(nan), std::invalid_argument);

  LemkeOptions bad;
  bad.tolerance = 0.0;
  CHECK_THROWS_WITH_AS(lemke(pos, bad), doctest::Contains("tolerance"), std::invalid_argument);
  LemkeOptions cover;
  cover.covering = (Vector(2) << 1.0, -1.0).finished();
  CHECK_THROWS_WITH_AS(lemke(pos, cover), doctest::Contains("covering(1)"), std::invalid_argument);
}

TEST_CASE("another covering vector gives the same unique solution") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 1 + trial % 12;
    const auto m = testing::manufacture(rng, testing::p_matrix(rng, n));
    LemkeOptions o;
    o.covering = testing::random_vector(rng, n, 0.1, 3.0);
    const Result r = lemke(m.problem, o);
    REQUIRE(r.ok());
    CHECK(relative_distance(r.z, m.z) < 1e-10);
  }
}

TEST_CASE("workspace reuse: one solver, varying sizes, same answers as fresh solvers") {
  std::mt19937 rng(3);
  Lemke solver(12);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + (trial * 5) % 12;
    const auto m = testing::manufacture(rng, testing::spd(rng, n, 100.0));
    const Result reused = solver.solve(m.problem);
    const Result fresh = lemke(m.problem);
    REQUIRE(reused.ok());
    CHECK(reused.iterations == fresh.iterations);
    CHECK((reused.z - fresh.z).lpNorm<Eigen::Infinity>() == 0.0);
    CHECK(lcp_violations(m.problem, reused.z, 1e-12).empty());
  }
  CHECK(solver.capacity() == 12);  // never grew: the workspace was reused

  // The allocation-free core writes into caller storage.
  const auto m = testing::manufacture(rng, testing::p_matrix(rng, 5));
  Vector z(5);
  const Status s = solver.run(m.problem.M, m.problem.q, LemkeOptions{}, z);
  CHECK(s == Status::kSolved);
  CHECK(relative_distance(z, m.z) < 1e-12);
  CHECK(solver.last_residual() <= LemkeOptions{}.tolerance);
}

// The in-place solve runs a core with n fixed at compile time for n <= 12 and one with a
// run-time n above. Both must give the solution that enumeration of the complementary bases
// finds (unique for a P-matrix), and the residuals of lcp::residual / lcp::siconos_error.
TEST_CASE("compile-time sizes n = 1..13: the enumeration's solution and the shared measures") {
  // Lemke's tableau and enumeration's block solve lose a few ulps times cond(M) = 10.
  constexpr double kAgree = 1e-10;
  std::mt19937 rng(13);
  Lemke solver(4);  // grows on demand; reused across sizes as an integrator would
  Result r;
  for (Eigen::Index n = 1; n <= 13; ++n) {
    for (int k = 0; k < 5; ++k) {
      INFO("n = " << n << ", problem " << k);
      const auto m = testing::manufacture(rng, testing::p_matrix(rng, n), 0.0);
      const Result oracle = enumerate(m.problem, EnumerationOptions{1e-12, 13});
      REQUIRE(oracle.ok());
      solver.solve(m.problem, LemkeOptions{}, r);
      REQUIRE(r.ok());
      CHECK(relative_distance(r.z, oracle.z) <= kAgree);
      CHECK(r.residual == residual(m.problem.M, m.problem.q, r.z));
      CHECK(r.siconos_error == doctest::Approx(siconos_error(m.problem.M, m.problem.q, r.z))
                                   .epsilon(1e-14));
      CHECK(relative_distance(r.w, m.problem.M * r.z + m.problem.q) <= 1e-14);
    }
  }
}

TEST_CASE("compile-time sizes: n = 1 by hand, max_pivots = 1, NaN anywhere throws") {
  // n = 1: M = [2], q = (-4): z = 2, w = 0; two pivots (z0 enters, then z1 replaces it).
  const Problem one = make((Matrix(1, 1) << 2).finished(), (Vector(1) << -4).finished());
  Lemke solver;
  Result r;
  solver.solve(one, LemkeOptions{}, r);
  REQUIRE(r.ok());
  CHECK(r.z(0) == 2.0);
  CHECK(r.w(0) == 0.0);
  CHECK(r.iterations == 2);
  LemkeOptions limit;
  limit.max_pivots = 1;
  std::mt19937 rng(5);
  for (Eigen::Index n = 1; n <= 12; ++n) {
    INFO("n = " << n);
    // Every z_i > 0: at least n + 1 pivots.
    Problem p;
    p.M = testing::p_matrix(rng, n);
    p.q = -p.M * Vector::Constant(n, 1.0);
    solver.solve(p, limit, r);
    CHECK(r.status == Status::kMaxIterations);
    CHECK(r.iterations == 1);
    Problem bad = p;
    bad.M(n - 1, 0) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH_AS(solver.solve(bad, LemkeOptions{}, r),
                         doctest::Contains(("M(" + std::to_string(n - 1) + ", 0)").c_str()),
                         std::invalid_argument);
    bad = p;
    bad.q(n - 1) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH_AS(solver.solve(bad, LemkeOptions{}, r),
                         doctest::Contains(("q(" + std::to_string(n - 1) + ")").c_str()),
                         std::invalid_argument);
  }
}
