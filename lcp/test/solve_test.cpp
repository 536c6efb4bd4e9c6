// Every solver through lcp::solve on shared random problem classes, checked against the
// defining conditions, the manufactured solution and each other; plus the shared edges.
#include "lcp/enumeration.hpp"
#include "lcp/solve.hpp"
#include "lcp/test/problems.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace nsb::lcp;
using testing::lcp_violations;
using testing::relative_distance;

namespace {
const Solver kAll[] = {Solver::kLemke, Solver::kPgs, Solver::kNewtonFb, Solver::kEnumeration};

// Forward error of a backward-stable answer: about cond(M) * 1e-16 relative, with a margin of
// 1e4 for the pivots/iterations that accumulate it.
double forward_tolerance(double cond) { return std::max(1e-11, cond * 1e-12); }
}  // namespace

TEST_CASE("solver names round-trip") {
  for (Solver s : kAll) CHECK(parse_solver(to_string(s)) == s);
  CHECK_FALSE(parse_solver("simplex").has_value());
}

TEST_CASE("SPD, condition numbers 1 to 1e8: every applicable solver recovers z*") {
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 90; ++trial) {
    const int n = 1 + trial % 12;
    const double cond = std::pow(10.0, trial % 9);
    const double scale = std::pow(10.0, (trial % 5) - 2);  // data from 1e-2 to 1e2
    const auto m = testing::manufacture(rng, testing::spd(rng, n, cond, scale), 0.1, scale);
    for (Solver s : kAll) {
      // PGS contracts at a rate ~ 1 - 1/cond: run it only where that is practical.
      if (s == Solver::kPgs && cond > 1e2) continue;
      INFO("trial " << trial << ", n = " << n << ", cond = " << cond << ", solver "
                    << to_string(s));
      const Result r = solve(m.problem, s);
      REQUIRE(r.ok());
      CHECK(r.residual <= SolveOptions{}.tolerance);
      CHECK(lcp_violations(m.problem, r.z, 1e-11).empty());
      CHECK(relative_distance(r.z, m.z) <= forward_tolerance(cond) * 1e3 / (scale < 1 ? scale : 1));
    }
  }
}

TEST_CASE("nonsymmetric P-matrices: Lemke, Newton-FB and enumeration agree on the unique z*") {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 80; ++trial) {
    const int n = 1 + trial % 12;
    const auto m = testing::manufacture(rng, testing::p_matrix(rng, n, 1.0 + trial), 0.1);
    for (Solver s : {Solver::kLemke, Solver::kNewtonFb, Solver::kEnumeration}) {
      INFO("trial " << trial << ", n = " << n << ", solver " << to_string(s));
      const Result r = solve(m.problem, s);
      REQUIRE(r.ok());
      CHECK(relative_distance(r.z, m.z) < 1e-9);
    }
  }
}

TEST_CASE("singular PSD: any valid solution, and w = M z + q is the same for all") {
  // For symmetric PSD M two solutions z1, z2 satisfy (z1 - z2)^T M (z1 - z2) <= 0, so
  // M z1 = M z2: w is unique even though z is not (Cottle, Pang & Stone, Thm 3.1.7).
  std::mt19937 rng(8);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 2 + trial % 11;
    const int rank = 1 + trial % (n - 1);
    const auto m = testing::manufacture(rng, testing::singular_psd(rng, n, rank), 0.1);
    for (Solver s : kAll) {
      INFO("trial " << trial << ", n = " << n << ", rank " << rank << ", solver "
                    << to_string(s));
      SolveOptions o;
      if (s == Solver::kPgs || s == Solver::kNewtonFb) {
        // Both converge only linearly where the solution set is not a point (PGS: Luo &
        // Tseng 1992; FB: the Jacobian is singular there), so ask for less.
        o.tolerance = 1e-9;
        o.max_iterations = 200000;
      }
      const Result r = solve(m.problem, s, o);
      if (s == Solver::kNewtonFb && !r.ok()) continue;  // may stall: checked in the verification
      REQUIRE(r.ok());
      CHECK(lcp_violations(m.problem, r.z, 1e-8).empty());
      CHECK(relative_distance(r.w, m.w) < (o.tolerance > 1e-12 ? 1e-6 : 1e-9));
    }
  }
}

TEST_CASE("edges shared by every solver") {
  for (Solver s : kAll) {
    INFO("solver " << to_string(s));
    Problem empty;
    const Result e = solve(empty, s);
    CHECK(e.ok());
    CHECK(e.z.size() == 0);

    Problem pos;
    pos.M = (Matrix(2, 2) << 3, -1, 2, 1).finished();
    pos.q = (Vector(2) << 0.0, 4.0).finished();
    const Result r = solve(pos, s);
    CHECK(r.ok());
    CHECK(r.z.isZero(0.0));

    Problem nan = pos;
    nan.q(1) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(solve(nan, s), std::invalid_argument);
    Problem inf = pos;
    inf.M(0, 1) = -std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(solve(inf, s), std::invalid_argument);
    Problem mismatch = pos;
    mismatch.q.resize(3);
    mismatch.q.setZero();
    CHECK_THROWS_AS(solve(mismatch, s), std::invalid_argument);
    SolveOptions bad;
    bad.tolerance = -1.0;
    CHECK_THROWS_WITH_AS(solve(pos, s, bad), doctest::Contains("tolerance"), std::invalid_argument);
  }
  // max_iterations = 1 on a problem that needs more: kMaxIterations for the iterative
  // solvers and for Lemke (whose limit counts pivots). Ill-conditioned (cond 1e6, n = 40):
  // Newton-FB's active-set step solves a well-conditioned n = 10 problem in one step.
  std::mt19937 rng(1);
  const auto m = testing::manufacture(rng, testing::spd(rng, 40, 1e6), 0.0);
  SolveOptions one;
  one.max_iterations = 1;
  for (Solver s : {Solver::kLemke, Solver::kPgs, Solver::kNewtonFb}) {
    INFO("solver " << to_string(s));
    const Result r = solve(m.problem, s, one);
    CHECK(r.status == Status::kMaxIterations);
    CHECK(r.iterations == 1);
  }
}

TEST_CASE("history is recorded on request") {
  std::mt19937 rng(2);
  const auto m = testing::manufacture(rng, testing::spd(rng, 6, 10.0));
  SolveOptions o;
  o.record_history = true;
  for (Solver s : {Solver::kPgs, Solver::kNewtonFb}) {
    const Result r = solve(m.problem, s, o);
    REQUIRE(r.ok());
    CHECK(r.history.size() == static_cast<std::size_t>(r.iterations) + 1);
    CHECK(r.history.back() == doctest::Approx(r.residual).epsilon(1e-12));
  }
}
