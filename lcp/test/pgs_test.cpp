// Projected Gauss–Seidel: hand sweeps, SOR, warm start, zero diagonal, monotone descent.
#include "lcp/pgs.hpp"
#include "lcp/test/problems.hpp"

#include <doctest/doctest.h>

#include <limits>
#include <random>
#include <string>

using namespace nsb::lcp;
using nsb::lcp::testing::relative_distance;

namespace {
// PGS stops at residual 1e-12; on these well-conditioned problems the error in z is of the
// same order times cond(M) <= 1e2.
constexpr double kConverged = 1e-9;

double objective(const Problem& p, const Vector& z) {
  return 0.5 * z.dot(p.M * z) + p.q.dot(z);
}
}  // namespace

TEST_CASE("hand-solved: a diagonal M is solved in one sweep") {
  // M = diag(2, 4), q = (-2, 4): z_1 = max(0, 0 - (-2)/2) = 1, z_2 = max(0, 0 - 4/4) = 0.
  Problem p;
  p.M = Vector(Vector::LinSpaced(2, 2.0, 4.0)).asDiagonal();
  p.q = (Vector(2) << -2.0, 4.0).finished();
  const Result r = pgs(p);
  REQUIRE(r.ok());
  CHECK(r.iterations == 1);
  CHECK(r.z(0) == 1.0);
  CHECK(r.z(1) == 0.0);
}

TEST_CASE("hand-solved: first sweep on M = [2 1; 1 2], q = (-5, -6)") {
  // Sweep 1 from 0: z_1 = 5/2; z_2 = max(0, (6 - 5/2)/2) = 7/4. Limit: (4/3, 7/3).
  Problem p;
  p.M = (Matrix(2, 2) << 2, 1, 1, 2).finished();
  p.q = (Vector(2) << -5, -6).finished();
  PgsOptions one;
  one.max_iterations = 1;
  const Result r1 = pgs(p, one);
  CHECK(r1.status == Status::kMaxIterations);
  CHECK(r1.z(0) == 2.5);
  CHECK(r1.z(1) == 1.75);
  const Result r = pgs(p);
  REQUIRE(r.ok());
  CHECK(relative_distance(r.z, (Vector(2) << 4.0 / 3.0, 7.0 / 3.0).finished()) < kConverged);
}

TEST_CASE("zero or negative diagonal is a status naming the entry") {
  Problem p;
  p.M = (Matrix(2, 2) << 1, 1, 1, 0).finished();
  p.q = (Vector(2) << -1, -1).finished();
  Result r = pgs(p);
  CHECK(r.status == Status::kZeroDiagonal);
  CHECK(r.message.find("M(1, 1)") != std::string::npos);
  p.M(1, 1) = -2.0;
  r = pgs(p);
  CHECK(r.status == Status::kZeroDiagonal);
}

TEST_CASE("SOR factors in (0, 2) converge on SPD problems; the objective never increases") {
  std::mt19937 rng(17);
  for (double omega : {0.5, 1.0, 1.3, 1.8}) {
    for (int trial = 0; trial < 10; ++trial) {
      const int n = 2 + trial * 3;
      const auto m = testing::manufacture(rng, testing::spd(rng, n, 30.0));
      PgsOptions o;
      o.relaxation = omega;
      const Result r = pgs(m.problem, o);
      INFO("omega = " << omega << ", trial " << trial);
      REQUIRE(r.ok());
      CHECK(relative_distance(r.z, m.z) < kConverged);
      // For symmetric M each relaxed coordinate step with omega in (0, 2) lowers
      // f(z) = 1/2 z^T M z + q^T z (Cottle, Pang & Stone §5.2), so f is monotone over sweeps.
      double previous = 0.0;  // f(0)
      for (int k = 1; k <= 8; ++k) {
        PgsOptions ok = o;
        ok.max_iterations = k;
        const double f = objective(m.problem, pgs(m.problem, ok).z);
        CHECK(f <= previous + 1e-12 * (1.0 + std::abs(previous)));
        previous = f;
      }
    }
  }
  PgsOptions bad;
  bad.relaxation = 2.0;
  Problem p;
  CHECK_THROWS_WITH_AS(pgs(p, bad), doctest::Contains("relaxation"), std::invalid_argument);
}

TEST_CASE("warm start: at the solution no sweep is needed, near it fewer") {
  std::mt19937 rng(4);
  const auto m = testing::manufacture(rng, testing::spd(rng, 20, 50.0));
  const Result cold = pgs(m.problem);
  REQUIRE(cold.ok());
  const Result at = pgs(m.problem, {}, cold.z);
  CHECK(at.ok());
  CHECK(at.iterations == 0);
  const Vector near = m.z + 1e-6 * testing::random_vector(rng, 20);
  const Result warm = pgs(m.problem, {}, near);
  CHECK(warm.ok());
  CHECK(warm.iterations < cold.iterations);
}

TEST_CASE("edges: n = 0, q >= 0, NaN") {
  Problem empty;
  CHECK(pgs(empty).ok());
  Problem p;
  p.M = Matrix::Identity(2, 2);
  p.q = (Vector(2) << 1, 0).finished();
  const Result r = pgs(p);
  CHECK(r.ok());
  CHECK(r.iterations == 0);
  p.q(0) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(pgs(p), std::invalid_argument);
}

// The in-place solve runs a core with n fixed at compile time for n <= 12 and one with a
// run-time n above: both reach the manufactured solution with lcp::residual's measures.
TEST_CASE("compile-time sizes n = 1..13: the manufactured solution and the shared measures") {
  std::mt19937 rng(21);
  Result r;
  for (Eigen::Index n = 1; n <= 13; ++n) {
    for (int k = 0; k < 3; ++k) {
      INFO("n = " << n << ", problem " << k);
      const auto m = testing::manufacture(rng, testing::spd(rng, n, 10.0), 0.0);
      pgs(m.problem, PgsOptions{}, r);
      REQUIRE(r.ok());
      CHECK(relative_distance(r.z, m.z) <= kConverged);
      CHECK(r.residual == residual(m.problem.M, m.problem.q, r.z));
      CHECK(r.siconos_error == doctest::Approx(siconos_error(m.problem.M, m.problem.q, r.z))
                                   .epsilon(1e-14));
    }
  }
}

// The refusal is decided from the diagonal before the rest of M is read. Its z = 0, w = q and
// measures must be those of lcp::residual and lcp::siconos_error at z = 0.
TEST_CASE("refusal: z = 0, w = q and their measures; what is read is checked, n = 1..13") {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::mt19937 rng(22);
  Result r;
  for (Eigen::Index n = 1; n <= 13; ++n) {
    INFO("n = " << n);
    Problem p;
    p.M = testing::spd(rng, n, 10.0);
    p.q = testing::random_vector(rng, n);
    const Eigen::Index bad = n / 2;
    p.M(bad, bad) = 0.0;
    pgs(p, PgsOptions{}, r);
    CHECK(r.status == Status::kZeroDiagonal);
    CHECK(r.iterations == 0);
    CHECK(r.z.isZero(0.0));
    CHECK(r.w == p.q);
    const Vector zero = Vector::Zero(n);
    CHECK(r.residual == residual(p.M, p.q, zero));
    CHECK(r.siconos_error == doctest::Approx(siconos_error(p.M, p.q, zero)).epsilon(1e-14));
    // The by-value form names the entry.
    CHECK(pgs(p).message.find("M(" + std::to_string(bad) + ", " + std::to_string(bad) + ")") !=
          std::string::npos);
    // A non-finite q or diagonal entry is a caller's mistake, refused or not.
    Problem nan_q = p;
    nan_q.q(n - 1) = kNaN;
    CHECK_THROWS_AS(pgs(nan_q, PgsOptions{}, r), std::invalid_argument);
    Problem nan_diagonal = p;
    nan_diagonal.M(bad, bad) = kNaN;
    CHECK_THROWS_AS(pgs(nan_diagonal, PgsOptions{}, r), std::invalid_argument);
    // Off the diagonal, M is not read when the problem is refused (documented in pgs.hpp);
    // when it is solved, every entry is checked.
    if (n > 1) {
      Problem nan_off = p;
      nan_off.M(n - 1, 0) = kNaN;
      pgs(nan_off, PgsOptions{}, r);
      CHECK(r.status == Status::kZeroDiagonal);
      nan_off.M(bad, bad) = 1.0;
      CHECK_THROWS_AS(pgs(nan_off, PgsOptions{}, r), std::invalid_argument);
    }
  }
}

TEST_CASE("edges of the in-place form: n = 0, n = 1 by hand, max_iterations = 1") {
  Result r;
  pgs(Problem{}, PgsOptions{}, r);
  CHECK(r.ok());
  CHECK(r.z.size() == 0);
  // n = 1: M = [4], q = (-2): z = 1/2 in one sweep (the exact coordinate minimiser).
  Problem one;
  one.M = (Matrix(1, 1) << 4).finished();
  one.q = (Vector(1) << -2).finished();
  pgs(one, PgsOptions{}, r);
  REQUIRE(r.ok());
  CHECK(r.z(0) == 0.5);
  CHECK(r.iterations == 1);
  // A coupled problem needs more than one sweep.
  std::mt19937 rng(23);
  PgsOptions once;
  once.max_iterations = 1;
  for (Eigen::Index n : {2, 12, 13}) {
    const auto m = testing::manufacture(rng, testing::spd(rng, n, 100.0), 0.0);
    pgs(m.problem, once, r);
    CHECK(r.status == Status::kMaxIterations);
    CHECK(r.iterations == 1);
  }
}
